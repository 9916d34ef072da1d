// Random walk of the disturbance acceleration, the a_dist row of Ward & Iagnemma eq. (10):
//
//   r = (a_dist_{k+1} - a_dist_k) / (q sqrt(dt))
//
// Parameter blocks: x_k (7), x_{k+1} (7). Use with a robust ceres::LossFunction (Huber/Cauchy):
// a hold-back is a jump, not a Gaussian increment; the loss lets a few steps carry it, which in
// the smoother plays the part of weak constraint 2 ("the disturbance acts quickly").
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/ward_state.h"

namespace slipgraph {

struct DisturbanceWalkFactor {
  explicit DisturbanceWalkFactor(double sd_per_step) : sqrt_information_(1.0 / sd_per_step) {}

  template <typename T>
  bool operator()(const T* x_k, const T* x_next, T* residual) const {
    residual[0] = sqrt_information_ * (x_next[ward::kAdist] - x_k[ward::kAdist]);
    return true;
  }

  static ceres::CostFunction* Create(double sd_per_step) {
    return new ceres::AutoDiffCostFunction<DisturbanceWalkFactor, 1, ward::kStateSize,
                                           ward::kStateSize>(
        new DisturbanceWalkFactor(sd_per_step));
  }

 private:
  double sqrt_information_;
};

}  // namespace slipgraph
