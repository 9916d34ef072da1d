// Weak constraint 5 of Ward & Iagnemma (Table I) as a smooth soft prior: magnitude bounds on
// v_bx, b_ax, a_dist and b_gz.
//
//   r_i = SmoothHinge(SmoothAbsolute(x_i) - max_i) / sd
//
// Zero well inside the bounds, linear outside. Parameter block: x_k (7).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <array>

#include "factors/component_autodiff.h"
#include "factors/smooth_hinge.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct BoundPrior {
  static constexpr int kBounded[4] = {ward::kVbx, ward::kAccelBias, ward::kAdist, ward::kGyroBias};
  static constexpr double kEps = 1e-3;

  BoundPrior(const std::array<double, 4>& max_abs, double sd)
      : max_abs_(max_abs), sqrt_information_(1.0 / sd) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int i = 0; i < 4; ++i) {
      residual[i] =
          sqrt_information_ * SmoothHinge(SmoothAbsolute(x[kBounded[i]], kEps) - max_abs_[i], kEps);
    }
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 4> kComponents{
        {{0, ward::kVbx}, {0, ward::kAccelBias}, {0, ward::kAdist}, {0, ward::kGyroBias}}};
  };
  static ceres::CostFunction* Create(const std::array<double, 4>& max_abs, double sd) {
    return new ComponentAutoDiffCostFunction<BoundPrior, Reads, 4, ward::kStateSize>(
        new BoundPrior(max_abs, sd));
  }

 private:
  std::array<double, 4> max_abs_;
  double sqrt_information_;
};

}  // namespace slipgraph
