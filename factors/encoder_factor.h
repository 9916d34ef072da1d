// Wheel encoder factor, Ward & Iagnemma eq. (11), rows 4 and 5:
//
//   r = ([w_l, w_r]_measured - [x_wl, x_wr]) / sd_w
//
// Parameter block: x_k (7). Driven side speeds in rad/s (io/measurement_stream DrivenSideSpeeds).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/component_autodiff.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct EncoderFactor {
  EncoderFactor(double omega_left_radps, double omega_right_radps, double sd_radps)
      : left_(omega_left_radps), right_(omega_right_radps), sqrt_information_(1.0 / sd_radps) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = sqrt_information_ * (left_ - x[ward::kOmegaLeft]);
    residual[1] = sqrt_information_ * (right_ - x[ward::kOmegaRight]);
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 2> kComponents{
        {{0, ward::kOmegaLeft}, {0, ward::kOmegaRight}}};
  };
  static ceres::CostFunction* Create(double omega_left_radps, double omega_right_radps,
                                     double sd_radps) {
    return new ComponentAutoDiffCostFunction<EncoderFactor, Reads, 2, ward::kStateSize>(
        new EncoderFactor(omega_left_radps, omega_right_radps, sd_radps));
  }

 private:
  double left_, right_;
  double sqrt_information_;
};

}  // namespace slipgraph
