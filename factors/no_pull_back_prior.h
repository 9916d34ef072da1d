// Weak constraint 3 of Ward & Iagnemma (Table I) as a smooth soft prior on the velocity: the
// disturbance may stop the robot but not pull it backwards.
//
//   r = SmoothHinge(-vel_dir v_bx, eps) / sd
//
// The EKF's form moves the disturbance to the force that would just hold the robot whenever the
// body moves against the wheels (solvers/weak_constraints.h); the smoother says what that form
// is for, on the velocity itself: zero while the body moves with its wheels or stands, growing
// linearly as it moves against them. vel_dir = sign(w_l + w_r) of the measured wheel speeds; the
// builder adds the factor only where the tires at standstill push the robot along vel_dir harder
// than gravity pulls it back (else rolling backwards is the slope's doing, not a disturbance's).
// Parameter block: x_k (7). sd: the constraint's density over sqrt(dt) (m/s).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/component_autodiff.h"
#include "factors/smooth_hinge.h"
#include "factors/ward_state.h"

namespace slipgraph {

struct NoPullBackPrior {
  static constexpr double kEpsMps = 0.002;

  NoPullBackPrior(double vel_dir, double sd_mps)
      : vel_dir_(vel_dir), sqrt_information_(1.0 / sd_mps) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = sqrt_information_ * SmoothHinge(-vel_dir_ * x[ward::kVbx], kEpsMps);
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 1> kComponents{{{0, ward::kVbx}}};
  };
  static ceres::CostFunction* Create(double vel_dir, double sd_mps) {
    return new ComponentAutoDiffCostFunction<NoPullBackPrior, Reads, 1, ward::kStateSize>(
        new NoPullBackPrior(vel_dir, sd_mps));
  }

 private:
  double vel_dir_;
  double sqrt_information_;
};

}  // namespace slipgraph
