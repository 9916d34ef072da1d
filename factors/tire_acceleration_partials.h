// The tire forces' accelerations of Ward & Iagnemma eqs. (1)-(2), f_tire (body x) and g_tire
// (yaw), with their partials with respect to the only states the tire forces read: v_bx,
// yaw_rate, w_l and w_r. One pass of 4-wide Jets through the shared tire physics
// (ComputeTireForces) serves both. In the accelerometer-driven form (the default) the EKF's
// prediction and the dynamics factor take their Jacobians from it, and so does the
// accelerometer factor with the model's law, instead of a Jet of the whole state; eq. (10) as
// printed still goes through Jets of the state.
#pragma once

#include <ceres/jet.h>

#include "factors/ward_dynamics.h"
#include "factors/ward_state.h"

namespace slipgraph {
namespace ward {

// An acceleration a (m/s^2 for f_tire, rad/s^2 for g_tire) and its partials: d a / d v_bx (per
// m/s), d a / d yaw_rate and d a / d w_l, d a / d w_r (per rad/s).
struct TireAccelerationPartials {
  double value;
  double d_v_bx;
  double d_yaw_rate;
  double d_omega_left;
  double d_omega_right;
};

struct TireAccelerations {
  TireAccelerationPartials body_x;  // f_tire, m/s^2
  TireAccelerationPartials yaw;     // g_tire, rad/s^2
};

inline TireAccelerations TireAccelerationsWithPartials(const double* x,
                                                       const AttitudeLoads<double>& loads,
                                                       const Params& p) {
  using Jet4 = ceres::Jet<double, 4>;
  Jet4 state[kStateSize];
  for (int i = 0; i < kStateSize; ++i) state[i] = Jet4(x[i]);
  state[kVbx].v[0] = 1.0;
  state[kYawRate].v[1] = 1.0;
  state[kOmegaLeft].v[2] = 1.0;
  state[kOmegaRight].v[3] = 1.0;
  const TireForces<Jet4> forces = ComputeTireForces(state, loads, p);
  const auto partials = [](const Jet4& a) {
    return TireAccelerationPartials{a.a, a.v[0], a.v[1], a.v[2], a.v[3]};
  };
  return {partials(forces.f_tire_mps2), partials(forces.g_tire_radps2)};
}

}  // namespace ward
}  // namespace slipgraph
