// Random walk of the driven wheel speeds, the w_l and w_r rows of Ward & Iagnemma eq. (10)
// (w' = 0 plus noise), as a factor of its own so it can carry a robust loss:
//
//   r = (w_{k+1} - w_k) / (q sqrt(dt))   for w_l and w_r
//
// Parameter blocks: x_k (7), x_{k+1} (7). The wheels of a speed-controlled robot hold their speed
// and then step to a new one; a Gaussian walk stiff enough to average out encoder quantization
// cannot follow the steps, a loose one follows the quantization (docs/smoother.md). With a Huber
// loss a small q smooths the quantization and the steps pass through a few large increments.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/ward_state.h"

namespace slipgraph {

struct WheelSpeedWalkFactor {
  explicit WheelSpeedWalkFactor(double sd_per_step) : sqrt_information_(1.0 / sd_per_step) {}

  template <typename T>
  bool operator()(const T* x_k, const T* x_next, T* residual) const {
    residual[0] = sqrt_information_ * (x_next[ward::kOmegaLeft] - x_k[ward::kOmegaLeft]);
    residual[1] = sqrt_information_ * (x_next[ward::kOmegaRight] - x_k[ward::kOmegaRight]);
    return true;
  }

  static ceres::CostFunction* Create(double sd_per_step) {
    return new ceres::AutoDiffCostFunction<WheelSpeedWalkFactor, 2, ward::kStateSize,
                                           ward::kStateSize>(new WheelSpeedWalkFactor(sd_per_step));
  }

 private:
  double sqrt_information_;
};

}  // namespace slipgraph
