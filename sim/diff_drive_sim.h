// The LAGR robot of Ward & Iagnemma: two driven front wheels with wheel-speed PI controllers and
// a motor torque limit, free rear castors. Longitudinal and yaw dynamics use the shared tire,
// rolling-resistance and normal-force laws (factors/) with the terrain's true coefficients, plus
// whatever effects the scenario switches on; hold-backs are a stiff damped tether.
#pragma once

#include <cstdint>

#include "sim/scenario.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace sim {

// Requires scenario.vehicle.type == kDiffDriveCastor.
SimResult SimulateDiffDrive(const Scenario& scenario, uint64_t seed);

}  // namespace sim
}  // namespace slipgraph
