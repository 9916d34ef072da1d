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
#include <ceres/jet.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "factors/ward_accel_driven_step.h"
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
      : params_(params),
        loads_(ward::ComputeAttitudeLoads(attitude, params)),
        dt_s_(dt_s),
        accel_input_mps2_(accel_input_mps2) {
    for (int i = 0; i < kResiduals; ++i) sqrt_information_[i] = 1.0 / sd_per_step[i];
  }

  template <typename T>
  bool operator()(const T* x_k, const T* x_next, const T* offsets, T* residual) const {
    T predicted[ward::kStateSize];
    Predict(x_k, offsets[0], predicted);
    for (int i = 0; i < kResiduals; ++i) {
      residual[i] = sqrt_information_[i] * (x_next[kRows[i]] - predicted[kRows[i]]);
    }
    return true;
  }

  // f(x_k, u_k, dt): x_k propagated over the step; accel_offset is c_ax (the gyro offset does
  // not enter the dynamics).
  template <typename T>
  void Predict(const T* x_k, const T& accel_offset, T* predicted) const {
    if (std::isnan(accel_input_mps2_)) {
      ward::Propagate(x_k, loads_, params_, dt_s_, predicted);
    } else {
      ward::PropagateWith(
          x_k,
          [&](const T* state, T* x_dot) {
            ward::StateDerivative(state, loads_, params_, x_dot);
            x_dot[ward::kVbx] = accel_input_mps2_ - accel_offset - state[ward::kAccelBias] -
                                loads_.gravity_along_x_mps2;
          },
          dt_s_, predicted);
    }
  }

  // f and its Jacobian d f / d [x_k, c_ax] by the chain rule through the RK4 stages
  // (factors/ward_accel_driven_step.h, as the EKF's prediction). Accelerometer-driven form only:
  // false, and nothing written, for eq. (10) as printed.
  using PredictionJacobian = Eigen::Matrix<double, ward::kStateSize, ward::kStateSize + 1>;
  bool PredictWithJacobian(const double* x_k, double accel_offset, double* predicted,
                           PredictionJacobian* J) const {
    if (std::isnan(accel_input_mps2_)) return false;
    Eigen::Matrix<double, ward::kStateSize, ward::kStateSize> A;
    Eigen::Matrix<double, ward::kStateSize, 1> d_specific_force;
    ward::PropagateAccelerometerDriven(x_k, accel_input_mps2_ - accel_offset, loads_, params_,
                                       dt_s_, predicted, &A, &d_specific_force);
    J->leftCols<ward::kStateSize>() = A;
    J->col(ward::kStateSize) = -d_specific_force;  // the specific force is a_x - c_ax
    return true;
  }

  // The factor as the problems use it: x_{k+1} enters linearly (its Jacobian is S on the rows'
  // columns), so only x_k and c_ax are differentiated: by the chain rule through RK4 in the
  // accelerometer-driven form, with 8-wide Jets for eq. (10) as printed, instead of the 16 an
  // automatic differentiation of all three blocks takes. Checked against CreateAutoDiff in
  // tests/ward_dynamics_factor_test.cpp.
  static ceres::CostFunction* Create(const ward::Params& params,
                                     const ward::Attitude<double>& attitude, double dt_s,
                                     double accel_input_mps2,
                                     const std::array<double, kResiduals>& sd_per_step);

  // The same factor by automatic differentiation of every block.
  static ceres::CostFunction* CreateAutoDiff(const ward::Params& params,
                                             const ward::Attitude<double>& attitude, double dt_s,
                                             double accel_input_mps2,
                                             const std::array<double, kResiduals>& sd_per_step) {
    return new ceres::AutoDiffCostFunction<WardDynamicsFactor, kResiduals, ward::kStateSize,
                                           ward::kStateSize, 2>(
        new WardDynamicsFactor(params, attitude, dt_s, accel_input_mps2, sd_per_step));
  }

  double sqrt_information(int i) const { return sqrt_information_[i]; }

 private:
  ward::Params params_;
  ward::AttitudeLoads<double> loads_;  // the attitude's normal forces and g sin(phi), once
  double dt_s_;
  double accel_input_mps2_;
  std::array<double, kResiduals> sqrt_information_;
};

class WardDynamicsCost final
    : public ceres::SizedCostFunction<WardDynamicsFactor::kResiduals, ward::kStateSize,
                                      ward::kStateSize, 2> {
 public:
  explicit WardDynamicsCost(const WardDynamicsFactor& factor) : factor_(factor) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    constexpr int kN = WardDynamicsFactor::kResiduals;
    const double* x_k = parameters[0];
    const double* x_next = parameters[1];
    const double* offsets = parameters[2];
    if (jacobians == nullptr) return factor_(x_k, x_next, offsets, residuals);
    double predicted[ward::kStateSize];
    WardDynamicsFactor::PredictionJacobian J;  // d f / d [x_k, c_ax]
    if (!factor_.PredictWithJacobian(x_k, offsets[0], predicted, &J)) {
      using Jet = ceres::Jet<double, ward::kStateSize + 1>;
      Jet x[ward::kStateSize], predicted_jet[ward::kStateSize];
      for (int j = 0; j < ward::kStateSize; ++j) x[j] = Jet(x_k[j], j);
      factor_.Predict(x, Jet(offsets[0], ward::kStateSize), predicted_jet);
      for (int r = 0; r < ward::kStateSize; ++r) {
        predicted[r] = predicted_jet[r].a;
        J.row(r) = predicted_jet[r].v.transpose();
      }
    }
    for (int i = 0; i < kN; ++i) {
      const int row = WardDynamicsFactor::kRows[i];
      const double s = factor_.sqrt_information(i);
      residuals[i] = s * (x_next[row] - predicted[row]);
      if (jacobians[0] != nullptr) {
        for (int j = 0; j < ward::kStateSize; ++j) {
          jacobians[0][i * ward::kStateSize + j] = -s * J(row, j);
        }
      }
      if (jacobians[1] != nullptr) {
        for (int j = 0; j < ward::kStateSize; ++j) jacobians[1][i * ward::kStateSize + j] = 0.0;
        jacobians[1][i * ward::kStateSize + row] = s;
      }
      if (jacobians[2] != nullptr) {
        jacobians[2][i * 2] = -s * J(row, ward::kStateSize);
        jacobians[2][i * 2 + 1] = 0.0;
      }
    }
    return true;
  }

 private:
  WardDynamicsFactor factor_;
};

inline ceres::CostFunction* WardDynamicsFactor::Create(
    const ward::Params& params, const ward::Attitude<double>& attitude, double dt_s,
    double accel_input_mps2, const std::array<double, kResiduals>& sd_per_step) {
  return new WardDynamicsCost(
      WardDynamicsFactor(params, attitude, dt_s, accel_input_mps2, sd_per_step));
}

}  // namespace slipgraph
