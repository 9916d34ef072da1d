// A tracked skid-steer robot (Rogers-Marcovitz, Seegmiller & Kelly): track speeds follow the
// commands through a first-order drive lag; the body moves with the nominal track velocity plus
// the terrain's slip u_s = C(u_n, g) alpha (factors/ipd_kinematics.h) and a stochastic part, a
// Gauss-Markov process with a short correlation time whose low-frequency density is the
// terrain's q (what IPD's Q calibrates); the pose integrates eq. (2). On a terrain with a
// `track_soil` (ipd35m) the slip comes instead from each track's shear against the soil
// (sim/track_soil.h), with the soil varying along the path under each track.
#pragma once

#include <cstdint>

#include "sim/scenario.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace sim {

SimResult SimulateSkidSteer(const Scenario& scenario, uint64_t seed);

}  // namespace sim
}  // namespace slipgraph
