#include "solvers/wilcox_velocity.h"

#include <cmath>

namespace slipgraph {

std::vector<BodyVelocityMeasurement> WilcoxBodyVelocity(const WilcoxResult& result,
                                                        double fallback_advance_sd_m) {
  std::vector<BodyVelocityMeasurement> out;
  if (result.sides.empty()) return out;
  const std::vector<WilcoxCycle>& first = result.sides.front().cycles;
  for (const WilcoxSide& side : result.sides) {
    if (side.cycles.size() != first.size()) return {};  // no pairing of different cycles
  }
  const double n = static_cast<double>(result.sides.size());
  for (size_t k = 1; k < first.size(); ++k) {
    const double duration = first[k].t - first[k - 1].t;
    if (!(duration > 0.0)) continue;
    double advance = 0.0, variance = 0.0;
    bool have_sd = true, shared = true;
    for (const WilcoxSide& side : result.sides) {
      const WilcoxCycle& c = side.cycles[k];
      advance += c.advance_m / n;
      if (!(std::isfinite(c.advance_sd_m) && c.advance_sd_m > 0.0)) have_sd = false;
      variance += c.advance_sd_m * c.advance_sd_m / (n * n);
      if (c.advance_m != first[k].advance_m) shared = false;
    }
    // The sides' mean of independent estimates has variance sum / n^2; sides sharing the advance
    // are one estimate, with its own sd.
    const double sd = !have_sd ? fallback_advance_sd_m
                      : shared ? first[k].advance_sd_m
                               : std::sqrt(variance);
    out.push_back(
        {0.5 * (first[k].t + first[k - 1].t), advance / duration, sd / duration, first[k].t});
  }
  return out;
}

}  // namespace slipgraph
