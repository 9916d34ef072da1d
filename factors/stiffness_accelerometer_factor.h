// The accelerometer factor with the tire law's slip stiffness as a slowly varying unknown: the
// terrain under the wheels is not the one the user's coefficients describe, and it changes. The
// traction of each driven wheel is the law at a scaled relative velocity,
//
//   F = N (C1 sgn~(s v_rel; At) + C2 s v_rel),   s = 1 + theta(t),
//
// so theta scales the law's slope at small slip (C1 At + C2, where a robot drives) and leaves its
// plateau (C1, which a hold-back reaches) alone. theta(t) is linear between two nodes of a
// walk (WardProblemOptions::stiffness_walk_sd):
//
//   r = (a_x - (f_tire(x; s) + c_ax + b_ax + a_dist)) / sd_a,  theta = (1 - u) theta_a + u theta_b.
//
// Parameter blocks: x_k (7), IMU offsets [c_ax, c_gz] (2), theta_a (1), theta_b (1). With
// theta = 0 it is AccelerometerFactor exactly (tests/stiffness_accelerometer_factor_test.cpp).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/imu_factor.h"
#include "factors/traction.h"
#include "factors/ward_dynamics.h"

namespace slipgraph {

// The accelerometer's model prediction without offsets, biases and a_dist, with the slip
// stiffness scaled by `scale`.
template <typename T, typename S>
inline T TireBalanceWithStiffness(const T* x, const ward::AttitudeLoads<double>& loads,
                                  const ward::Params& p, const S& scale) {
  const ward::TireForces<T> forces = ward::ComputeTireForces(x, loads, p);
  const T scaled = TractionForceN(loads.driven_left_n, scale * forces.v_rel_left_mps, p.tire) +
                   TractionForceN(loads.driven_right_n, scale * forces.v_rel_right_mps, p.tire);
  return forces.f_tire_mps2 +
         (scaled - forces.traction_left_n - forces.traction_right_n) / p.mass_kg;
}

struct StiffnessAccelerometerFactor {
  StiffnessAccelerometerFactor(const ward::Params& params, const ward::Attitude<double>& attitude,
                               double accel_x_mps2, double sd_mps2, double weight_b)
      : reading_(params, attitude, accel_x_mps2, sd_mps2), weight_b_(weight_b) {}

  template <typename T>
  bool operator()(const T* x, const T* offsets, const T* theta_a, const T* theta_b,
                  T* residual) const {
    const T scale = T(1.0) + (1.0 - weight_b_) * theta_a[0] + weight_b_ * theta_b[0];
    residual[0] = reading_.Residual(
        TireBalanceWithStiffness(x, reading_.loads, reading_.params, scale), x, offsets);
    return true;
  }

  static ceres::CostFunction* Create(const ward::Params& params,
                                     const ward::Attitude<double>& attitude, double accel_x_mps2,
                                     double sd_mps2, double weight_b) {
    return new ceres::AutoDiffCostFunction<StiffnessAccelerometerFactor, 1, ward::kStateSize, 2, 1,
                                           1>(
        new StiffnessAccelerometerFactor(params, attitude, accel_x_mps2, sd_mps2, weight_b));
  }

 private:
  AccelerometerReading reading_;
  double weight_b_;  // u: theta_b's share of the sample's theta
};

}  // namespace slipgraph
