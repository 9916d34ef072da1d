// A Diagnosis as the JSON object `diagnose --json` writes and the Python module returns.
#pragma once

#include <nlohmann/json.hpp>

#include "workbench/diagnosis.h"

namespace slipgraph {

nlohmann::json ToJson(const Diagnosis& diagnosis);

}  // namespace slipgraph
