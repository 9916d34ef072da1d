// A layer check control: a problem builder that includes a solver (an include pointing up).
#pragma once
#include "solvers/ekf_runner.h"
