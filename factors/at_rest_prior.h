// Weak constraint 4 of Ward & Iagnemma (Table I): when both wheels have been stopped for
// t_stop, the walking biases and the disturbance tend to zero.
//
//   r = [b_ax / sd, a_dist / sd, b_gz / sd_gyro]
//
// The condition is on the measured wheel speeds (data), decided by the problem builder.
// Parameter block: x_k (7).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/component_autodiff.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct AtRestPrior {
  AtRestPrior(double sd_mps2, double sd_gyro_radps)
      : sqrt_information_(1.0 / sd_mps2), sqrt_information_gyro_(1.0 / sd_gyro_radps) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = sqrt_information_ * x[ward::kAccelBias];
    residual[1] = sqrt_information_ * x[ward::kAdist];
    residual[2] = sqrt_information_gyro_ * x[ward::kGyroBias];
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 3> kComponents{
        {{0, ward::kAccelBias}, {0, ward::kAdist}, {0, ward::kGyroBias}}};
  };
  static ceres::CostFunction* Create(double sd_mps2, double sd_gyro_radps) {
    return new ComponentAutoDiffCostFunction<AtRestPrior, Reads, 3, ward::kStateSize>(
        new AtRestPrior(sd_mps2, sd_gyro_radps));
  }

 private:
  double sqrt_information_;
  double sqrt_information_gyro_;
};

}  // namespace slipgraph
