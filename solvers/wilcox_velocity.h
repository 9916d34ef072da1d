// Wilcox's advance offered to the vehicle graph (issue 8): each cycle's advance of the rear wheels
// over its duration is the rover's mean velocity along body x then, a measurement the batch and
// window smoothers take like a GNSS velocity (problems/ward_factor_source.h). On a rocker-bogie
// log without GNSS it is what ties the velocity to the ground when the wheels slip.
#pragma once

#include <vector>

#include "problems/ward_factor_source.h"
#include "solvers/wilcox_baseline.h"

namespace slipgraph {

// One measurement per cycle (the sides' mean advance; both sides must have the same cycles), at
// the cycle's middle, sd = the advance's sd / the cycle's duration: the graph's marginal sd when
// it has one (WilcoxCycle::advance_sd_m), else fallback_advance_sd_m; available at the cycle's
// end (its scan). The baseline's advances are causal (each cycle's search sees scans up to its
// own, its learned law cycles before), so an online window may take them as they come; the
// graph's are not (its final solve sees the whole traverse).
std::vector<BodyVelocityMeasurement> WilcoxBodyVelocity(const WilcoxResult& result,
                                                        double fallback_advance_sd_m);

}  // namespace slipgraph
