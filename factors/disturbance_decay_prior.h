// Weak constraint 2 of Ward & Iagnemma (Table I) in the smoother: "the disturbance should act
// quickly" — a disturbance that creeps up while the wheels barely slip is pulled back toward
// zero. As a soft prior on every state:
//
//   r = a_dist / sd,   with a robust loss (Cauchy) chosen by the problem builder
//
// Near zero it is quadratic (small, slow disturbances decay, as WC2's alpha x3 does); a large
// disturbance that the accelerometer and the tire law insist on (a hold-back) pays an almost
// flat cost and stays. Without it, a_dist and v_bx can drift together along the tire law, which the
// accelerometer alone cannot see (docs/ekf.md). Parameter block: x_k (7).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/component_autodiff.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct DisturbanceDecayPrior {
  explicit DisturbanceDecayPrior(double sd_mps2) : sqrt_information_(1.0 / sd_mps2) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = sqrt_information_ * x[ward::kAdist];
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 1> kComponents{{{0, ward::kAdist}}};
  };
  static ceres::CostFunction* Create(double sd_mps2) {
    return new ComponentAutoDiffCostFunction<DisturbanceDecayPrior, Reads, 1, ward::kStateSize>(
        new DisturbanceDecayPrior(sd_mps2));
  }

 private:
  double sqrt_information_;
};

}  // namespace slipgraph
