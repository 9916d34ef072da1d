// One step of eq. (10) in the accelerometer-driven form (docs/ekf.md, change 1) and its
// state-transition matrix, for the EKF's prediction:
//
//   v_bx'     = a_x - c_ax - b_ax - g sin(phi)      (a_x - c_ax held over the step)
//   b_ax'     = -b_ax / tau_ax
//   yaw_rate' = g_tire(v_bx, yaw_rate, w_l, w_r)    eq. (2), factors/ward_dynamics.h
//   b_gz'     = -b_gz / tau_gz,   a_dist, w_l, w_r constant.
//
// The state comes from the same classical RK4 on the same sub-steps as PropagateWith (the same
// arithmetic, so the same bits as a Jet pass through it). The transition matrix A = d x_next / d x
// comes from the chain rule through the stages: only eight entries differ from the identity
// (d v/d b_ax, d b_ax/d b_ax, d yaw_rate/d [v_bx, b_ax, w_l, w_r, yaw_rate], d b_gz/d b_gz), and
// each stage needs only the yaw acceleration's four partials, from 4-wide Jets of the shared tire
// physics (ComputeTireForces). The 7-wide Jet pass through all four stages it replaces was about
// 45 % of an EKF step (perf, docs/ekf.md). Tested against that pass
// (tests/ward_accel_driven_step_test.cpp). The dynamics factor takes its Jacobians from here too,
// with the column of the specific force (through it, the accelerometer offset c_ax).
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "factors/tire_acceleration_partials.h"
#include "factors/ward_dynamics.h"
#include "factors/ward_state.h"

namespace slipgraph {
namespace ward {

// x_next = x propagated over dt_s; A = d x_next / d x. specific_force_mps2 is a_x - c_ax.
// d_specific_force, when given: d x_next / d specific_force_mps2 (non-zero in v_bx and yaw_rate).
inline void PropagateAccelerometerDriven(
    const double* x, double specific_force_mps2, const AttitudeLoads<double>& loads,
    const Params& p, double dt_s, double* x_next, Eigen::Matrix<double, kStateSize, kStateSize>* A,
    Eigen::Matrix<double, kStateSize, 1>* d_specific_force = nullptr, double max_substep_s = 0.01) {
  // The non-identity entries of d state / d x, in this order, then d [v_bx, yaw_rate] / d a_x.
  enum Entry : int { kVB, kBB, kYV, kYB, kYWl, kYWr, kYY, kGG, kVA, kYA, kEntries };
  using Sensitivity = Eigen::Matrix<double, kEntries, 1>;
  const double gravity_along_x = loads.gravity_along_x_mps2;

  // The derivative at a stage, value and sensitivity, in the arithmetic of StateDerivative with
  // the accelerometer-driven v_bx' (so that the values match PropagateWith's to the bit).
  const auto derivative = [&](const double* s, const Sensitivity& ds, double* s_dot,
                              Sensitivity* ds_dot) {
    const TireAccelerationPartials g = TireAccelerationsWithPartials(s, loads, p).yaw;
    s_dot[kVbx] = specific_force_mps2 - s[kAccelBias] - gravity_along_x;
    s_dot[kAccelBias] = -s[kAccelBias] / p.accel_bias_tau_s;
    s_dot[kAdist] = 0.0;
    s_dot[kOmegaLeft] = 0.0;
    s_dot[kOmegaRight] = 0.0;
    s_dot[kYawRate] = g.value;
    s_dot[kGyroBias] = -s[kGyroBias] / p.gyro_bias_tau_s;
    // d v_bx / d v_bx stays 1 and the wheel speeds are constant, so:
    (*ds_dot)(kVB) = -ds(kBB);
    (*ds_dot)(kBB) = -ds(kBB) / p.accel_bias_tau_s;
    (*ds_dot)(kYV) = g.d_v_bx + g.d_yaw_rate * ds(kYV);
    (*ds_dot)(kYB) = g.d_v_bx * ds(kVB) + g.d_yaw_rate * ds(kYB);
    (*ds_dot)(kYWl) = g.d_omega_left + g.d_yaw_rate * ds(kYWl);
    (*ds_dot)(kYWr) = g.d_omega_right + g.d_yaw_rate * ds(kYWr);
    (*ds_dot)(kYY) = g.d_yaw_rate * ds(kYY);
    (*ds_dot)(kGG) = -ds(kGG) / p.gyro_bias_tau_s;
    (*ds_dot)(kVA) = 1.0;
    (*ds_dot)(kYA) = g.d_v_bx * ds(kVA) + g.d_yaw_rate * ds(kYA);
  };

  const int substeps = dt_s > max_substep_s ? static_cast<int>(std::ceil(dt_s / max_substep_s)) : 1;
  const double h = dt_s / substeps;
  double state[kStateSize], k1[kStateSize], k2[kStateSize], k3[kStateSize], k4[kStateSize],
      tmp[kStateSize];
  Sensitivity ds = Sensitivity::Zero(), dk1, dk2, dk3, dk4, dtmp;
  ds(kBB) = ds(kYY) = ds(kGG) = 1.0;
  for (int i = 0; i < kStateSize; ++i) state[i] = x[i];
  for (int step = 0; step < substeps; ++step) {
    derivative(state, ds, k1, &dk1);
    for (int i = 0; i < kStateSize; ++i) tmp[i] = state[i] + 0.5 * h * k1[i];
    dtmp = ds + 0.5 * h * dk1;
    derivative(tmp, dtmp, k2, &dk2);
    for (int i = 0; i < kStateSize; ++i) tmp[i] = state[i] + 0.5 * h * k2[i];
    dtmp = ds + 0.5 * h * dk2;
    derivative(tmp, dtmp, k3, &dk3);
    for (int i = 0; i < kStateSize; ++i) tmp[i] = state[i] + h * k3[i];
    dtmp = ds + h * dk3;
    derivative(tmp, dtmp, k4, &dk4);
    for (int i = 0; i < kStateSize; ++i) {
      state[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    ds += h / 6.0 * (dk1 + 2.0 * dk2 + 2.0 * dk3 + dk4);
  }
  for (int i = 0; i < kStateSize; ++i) x_next[i] = state[i];
  A->setIdentity();
  (*A)(kVbx, kAccelBias) = ds(kVB);
  (*A)(kAccelBias, kAccelBias) = ds(kBB);
  (*A)(kYawRate, kVbx) = ds(kYV);
  (*A)(kYawRate, kAccelBias) = ds(kYB);
  (*A)(kYawRate, kOmegaLeft) = ds(kYWl);
  (*A)(kYawRate, kOmegaRight) = ds(kYWr);
  (*A)(kYawRate, kYawRate) = ds(kYY);
  (*A)(kGyroBias, kGyroBias) = ds(kGG);
  if (d_specific_force != nullptr) {
    d_specific_force->setZero();
    (*d_specific_force)(kVbx) = ds(kVA);
    (*d_specific_force)(kYawRate) = ds(kYA);
  }
}

}  // namespace ward
}  // namespace slipgraph
