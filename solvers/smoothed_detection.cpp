#include "solvers/smoothed_detection.h"

#include <algorithm>

namespace slipgraph {

using namespace ward;  // NOLINT: state indices

void DetectImmobilizationOnSmoothedStates(const ModelConfig& model, const Vehicle& vehicle,
                                          double min_duration_s,
                                          std::vector<WardEstimate>* estimates) {
  std::vector<bool> raw(estimates->size(), false);
  for (size_t k = 0; k < estimates->size(); ++k) {
    WardEstimate& e = (*estimates)[k];
    const InstantSlip instant =
        ComputeInstantSlip(model.immobilization, vehicle.wheel_radius_m, vehicle.track_width_m,
                           e.x[kVbx], e.x[kYawRate], e.x[kOmegaLeft], e.x[kOmegaRight]);
    e.slip = instant.estimate;
    e.slip.slip_ema = 0.5 * (e.slip.slip_left + e.slip.slip_right);  // smoothed: no EMA needed
    raw[k] = instant.wheels_turning && !e.slip.braking && e.slip.slip_ema > e.slip.threshold;
  }
  // Keep runs that last at least min_duration.
  size_t k = 0;
  while (k < raw.size()) {
    size_t end = k;
    while (end < raw.size() && raw[end]) ++end;
    const bool keep = end > k && (*estimates)[end - 1].t - (*estimates)[k].t >= min_duration_s;
    for (size_t i = k; i < end; ++i) (*estimates)[i].slip.immobilized = keep;
    if (end == k) (*estimates)[k].slip.immobilized = false;
    k = std::max(end, k + 1);
  }
}

}  // namespace slipgraph
