#include "solvers/wilcox_velocity.h"

namespace slipgraph {

std::vector<BodyVelocityMeasurement> WilcoxBodyVelocity(const WilcoxResult& result,
                                                        double advance_sd_m) {
  std::vector<BodyVelocityMeasurement> out;
  if (result.sides.empty()) return out;
  const std::vector<WilcoxCycle>& first = result.sides.front().cycles;
  for (size_t k = 1; k < first.size(); ++k) {
    const double duration = first[k].t - first[k - 1].t;
    if (!(duration > 0.0)) continue;
    double advance = 0.0;
    bool complete = true;
    for (const WilcoxSide& side : result.sides) {
      if (side.cycles.size() != first.size()) complete = false;
      if (complete) advance += side.cycles[k].advance_m / result.sides.size();
    }
    if (!complete) return {};
    out.push_back(
        {0.5 * (first[k].t + first[k - 1].t), advance / duration, advance_sd_m / duration});
  }
  return out;
}

}  // namespace slipgraph
