// Weak constraint 1 of Ward & Iagnemma (Table I) as a smooth soft prior: the disturbance only
// opposes motion.
//
//   r = SmoothHinge(vel_dir a_dist, eps) / sd
//
// vel_dir = sign(w_l + w_r) of the measured wheel speeds (+1 or -1; the builder adds no factor at
// 0). Zero when the disturbance opposes the drive direction, growing linearly when it pushes.
// Parameter block: x_k (7). sd: the constraint's density over sqrt(dt) (m/s^2).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/component_autodiff.h"
#include "factors/smooth_hinge.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct OpposeMotionPrior {
  static constexpr double kEpsMps2 = 0.01;

  OpposeMotionPrior(double vel_dir, double sd_mps2)
      : vel_dir_(vel_dir), sqrt_information_(1.0 / sd_mps2) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = sqrt_information_ * SmoothHinge(vel_dir_ * x[ward::kAdist], kEpsMps2);
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 1> kComponents{{{0, ward::kAdist}}};
  };
  static ceres::CostFunction* Create(double vel_dir, double sd_mps2) {
    return new ComponentAutoDiffCostFunction<OpposeMotionPrior, Reads, 1, ward::kStateSize>(
        new OpposeMotionPrior(vel_dir, sd_mps2));
  }

 private:
  double vel_dir_;
  double sqrt_information_;
};

}  // namespace slipgraph
