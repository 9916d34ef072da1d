// Dynamics factor between consecutive Ward states, Ward & Iagnemma eq. (10) discretized exactly
// as the EKF does (factors/ward_dynamics.h, RK4 over dt):
//
//   r = S (x_{k+1} - f(x_k, u_k, dt))        over [v_bx, b_ax, w_l, w_r, yaw_rate, b_gz]
//
// Parameter blocks: x_k (7), x_{k+1} (7), IMU offsets [c_ax, c_gz] (2). u_k: the attitude at t_k
// (REP-103 roll and pitch, rad) and, in the accelerometer-driven form, the accelerometer x
// reading that covers [t_k, t_{k+1}] (the sample stamped t_{k+1}, a mean over the interval;
// m/s^2): v' = a_x - c_ax - b_ax - g sin(phi). S: the inverse
// process-noise standard deviations per step. a_dist has its own random-walk factor
// (state_walk_factor.h) so that a robust loss can let it jump.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <array>
#include <cmath>

#include "factors/frames.h"
#include "factors/ward_dynamics.h"

namespace slipgraph {

struct WardDynamicsFactor {
  static constexpr int kResiduals = 6;
  static constexpr int kRows[kResiduals] = {ward::kVbx,        ward::kAccelBias, ward::kOmegaLeft,
                                            ward::kOmegaRight, ward::kYawRate,   ward::kGyroBias};

  // accel_input_mps2: NaN selects eq. (10) as printed (v' from the tire law).
  WardDynamicsFactor(const ward::Params& params, const ward::Attitude<double>& attitude,
                     double dt_s, double accel_input_mps2,
                     const std::array<double, kResiduals>& sd_per_step)
      : params_(params), attitude_(attitude), dt_s_(dt_s), accel_input_mps2_(accel_input_mps2) {
    for (int i = 0; i < kResiduals; ++i) sqrt_information_[i] = 1.0 / sd_per_step[i];
  }

  template <typename T>
  bool operator()(const T* x_k, const T* x_next, const T* offsets, T* residual) const {
    using std::sin;
    T predicted[ward::kStateSize];
    if (std::isnan(accel_input_mps2_)) {
      ward::Propagate(x_k, attitude_, params_, dt_s_, predicted);
    } else {
      const double gravity_along_x =
          params_.gravity_mps2 * sin(WardPitchUphillRad(attitude_.pitch_rad));
      ward::PropagateWith(
          x_k,
          [&](const T* state, T* x_dot) {
            ward::StateDerivative(state, attitude_, params_, x_dot);
            x_dot[ward::kVbx] =
                accel_input_mps2_ - offsets[0] - state[ward::kAccelBias] - gravity_along_x;
          },
          dt_s_, predicted);
    }
    for (int i = 0; i < kResiduals; ++i) {
      residual[i] = sqrt_information_[i] * (x_next[kRows[i]] - predicted[kRows[i]]);
    }
    return true;
  }

  static ceres::CostFunction* Create(const ward::Params& params,
                                     const ward::Attitude<double>& attitude, double dt_s,
                                     double accel_input_mps2,
                                     const std::array<double, kResiduals>& sd_per_step) {
    return new ceres::AutoDiffCostFunction<WardDynamicsFactor, kResiduals, ward::kStateSize,
                                           ward::kStateSize, 2>(
        new WardDynamicsFactor(params, attitude, dt_s, accel_input_mps2, sd_per_step));
  }

 private:
  ward::Params params_;
  ward::Attitude<double> attitude_;
  double dt_s_;
  double accel_input_mps2_;
  std::array<double, kResiduals> sqrt_information_;
};

}  // namespace slipgraph
