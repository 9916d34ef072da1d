// Random walk of chosen state components between consecutive Ward states, rows of Ward &
// Iagnemma eq. (10) (x_i' = 0 plus noise) as factors of their own so they can carry a robust
// loss:
//
//   r_j = (x_{k+1}[i_j] - x_k[i_j]) / (q sqrt(dt))   for each index i_j
//
// Parameter blocks: x_k (7), x_{k+1} (7).
//
// DisturbanceWalkFactor (a_dist): use with a robust ceres::LossFunction (Huber/Cauchy): a
// hold-back is a jump, not a Gaussian increment; the loss lets a few steps carry it, which in the
// smoother plays the part of weak constraint 2 ("the disturbance acts quickly").
//
// WheelSpeedWalkFactor (w_l, w_r): the wheels of a speed-controlled robot hold their speed and
// then step to a new one; a Gaussian walk stiff enough to average out encoder noise cannot follow
// the steps, a loose one follows the noise (docs/smoother.md). With a Huber loss a small q smooths
// the noise and the steps pass through a few large increments.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/ward_state.h"

namespace slipgraph {

template <int... kIndices>
struct StateWalkFactor {
  static constexpr int kResiduals = sizeof...(kIndices);

  explicit StateWalkFactor(double sd_per_step) : sqrt_information_(1.0 / sd_per_step) {}

  template <typename T>
  bool operator()(const T* x_k, const T* x_next, T* residual) const {
    int j = 0;
    ((residual[j++] = sqrt_information_ * (x_next[kIndices] - x_k[kIndices])), ...);
    return true;
  }

  static ceres::CostFunction* Create(double sd_per_step) {
    return new ceres::AutoDiffCostFunction<StateWalkFactor, kResiduals, ward::kStateSize,
                                           ward::kStateSize>(new StateWalkFactor(sd_per_step));
  }

 private:
  double sqrt_information_;
};

using DisturbanceWalkFactor = StateWalkFactor<ward::kAdist>;
using WheelSpeedWalkFactor = StateWalkFactor<ward::kOmegaLeft, ward::kOmegaRight>;

}  // namespace slipgraph
