// Wilcox's measurements as Ceres factors on profile nodes (factors/wilcox_profile.h), one side:
//
//   range:        r = (z - [y(x_k + d) - (ybar(x_k) - s(x_k))]) / sd_range
//   articulation: r = (z - [(ybar - s)(x_k + n A) - (ybar - s)(x_k)]) / sd       (n = 1, 2)
//
// x_k the rear wheel's contact position at cycle k, y the undisturbed terrain (what the ranging
// sensor sees), s the sinkage, ybar the terrain averaged over a wheel's contact patch (what a
// wheel rides on, with s). Parameter blocks, all of size 1 (DynamicAutoDiffCostFunction): x_k,
// the y nodes near the rear wheel, the y nodes near x_k + offset, the s nodes near the rear
// wheel, the s nodes near x_k + offset (none for a range factor). The runs are fixed when the
// factor is built, with a margin for x_k to move.
#pragma once

#include <ceres/dynamic_autodiff_cost_function.h>

#include <vector>

#include "factors/wilcox_profile.h"

namespace slipgraph {

struct WilcoxMeasurementFactor {
  enum Kind { kRange, kArticulation };
  Kind kind;
  double offset_m;  // d (range) or n A (articulation)
  double measured_m;
  double sd_m;
  double patch_m;
  wilcox::GridRun y_near, y_far, s_near, s_far;  // s_far.count == 0 for a range factor

  int BlockCount() const { return 1 + y_near.count + y_far.count + s_near.count + s_far.count; }

  template <typename T>
  bool operator()(T const* const* p, T* residual) const {
    const T& x = p[0][0];
    T const* const* y_n = p + 1;
    T const* const* y_f = y_n + y_near.count;
    T const* const* s_n = y_f + y_far.count;
    T const* const* s_f = s_n + s_near.count;
    const T ride_rear =
        wilcox::WheelProfileAt(y_near, y_n, x, patch_m) - wilcox::ProfileAt(s_near, s_n, x);
    const T at = x + offset_m;
    T predicted;
    if (kind == kRange) {
      predicted = wilcox::ProfileAt(y_far, y_f, at) - ride_rear;
    } else {
      predicted = wilcox::WheelProfileAt(y_far, y_f, at, patch_m) -
                  wilcox::ProfileAt(s_far, s_f, at) - ride_rear;
    }
    residual[0] = (measured_m - predicted) / sd_m;
    return true;
  }

  // The caller adds the blocks in order: x, y near, y far, s near, s far.
  static ceres::CostFunction* Create(const WilcoxMeasurementFactor& factor) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<WilcoxMeasurementFactor, 4>(
        new WilcoxMeasurementFactor(factor));
    for (int i = 0; i < factor.BlockCount(); ++i) cost->AddParameterBlock(1);
    cost->SetNumResiduals(1);
    return cost;
  }
};

}  // namespace slipgraph
