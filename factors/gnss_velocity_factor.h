// GNSS velocity factor, Ward & Iagnemma eq. (11), row 3:
//
//   r = (v_gnss . x_body - v_bx) / sd_v
//
// where v_gnss . x_body is the ENU velocity projected on the body x axis (computed by the
// problem builder from the attitude; m/s). Parameter block: x_k (7).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/component_autodiff.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct GnssVelocityFactor {
  GnssVelocityFactor(double v_along_body_x_mps, double sd_mps)
      : measured_(v_along_body_x_mps), sqrt_information_(1.0 / sd_mps) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = sqrt_information_ * (measured_ - x[ward::kVbx]);
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 1> kComponents{{{0, ward::kVbx}}};
  };
  static ceres::CostFunction* Create(double v_along_body_x_mps, double sd_mps) {
    return new ComponentAutoDiffCostFunction<GnssVelocityFactor, Reads, 1, ward::kStateSize>(
        new GnssVelocityFactor(v_along_body_x_mps, sd_mps));
  }

 private:
  double measured_;
  double sqrt_information_;
};

}  // namespace slipgraph
