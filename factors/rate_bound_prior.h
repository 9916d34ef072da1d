// Weak constraint 6 of Ward & Iagnemma (Table I) as a smooth soft prior between consecutive
// states: limits on the rate of change of v_bx and b_ax,
//
//   r_i = SmoothHinge(SmoothAbsolute(x_{k+1,i} - x_{k,i}) / dt - max_rate_i) / sd
//
// zero while the state changes slower than its limit, linear beyond. Parameter blocks: x_k (7),
// x_{k+1} (7).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <array>

#include "factors/component_autodiff.h"
#include "factors/smooth_hinge.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct RateBoundPrior {
  static constexpr int kBounded[2] = {ward::kVbx, ward::kAccelBias};
  static constexpr double kEps = 1e-3;

  RateBoundPrior(const std::array<double, 2>& max_rate, double dt_s, double sd)
      : max_rate_(max_rate), dt_s_(dt_s), sqrt_information_(1.0 / sd) {}

  template <typename T>
  bool operator()(const T* x, const T* x_next, T* residual) const {
    for (int i = 0; i < 2; ++i) {
      const T rate = SmoothAbsolute(x_next[kBounded[i]] - x[kBounded[i]], kEps * dt_s_) / dt_s_;
      residual[i] = sqrt_information_ * SmoothHinge(rate - max_rate_[i], kEps);
    }
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 4> kComponents{
        {{0, ward::kVbx}, {0, ward::kAccelBias}, {1, ward::kVbx}, {1, ward::kAccelBias}}};
  };
  static ceres::CostFunction* Create(const std::array<double, 2>& max_rate, double dt_s,
                                     double sd) {
    return new ComponentAutoDiffCostFunction<RateBoundPrior, Reads, 2, ward::kStateSize,
                                             ward::kStateSize>(
        new RateBoundPrior(max_rate, dt_s, sd));
  }

 private:
  std::array<double, 2> max_rate_;
  double dt_s_;
  double sqrt_information_;
};

}  // namespace slipgraph
