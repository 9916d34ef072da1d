// Longitudinal and yaw dynamics of Ward & Iagnemma, eqs. (1), (2) and the state derivative (10).
//
//   v_bx'     = f_tire + a_dist - g sin(phi)                                  (1)
//   f_tire    = ( sum_driven F_traction + sum_all F_roll ) / m
//   yaw_rate' = g_tire = c / (2 J) ( F_right - F_left ),  F_side = F_traction + F_roll     (2)
//   x'        = [ v_bx', -b_ax / tau_ax, 0, 0, 0, yaw_rate', -b_gz / tau_gz ]              (10)
//
// Tire forward speeds v_fwd = v_bx -/+ c/2 yaw_rate (left/right; REP-103 yaw is counter-clockwise,
// so a left turn speeds the right wheel up). Ward's eq. (2) is written in a z-down frame
// (F1 - F2 with 1 = left); here it is in z-up REP-103, hence F_right - F_left. The wheel
// controller term of (10) is neglected, as in the paper (its effect is in the process noise).
// Rear castors of diff_drive_castor roll with the same track and contribute rolling resistance
// only; all-wheel-drive types use each side's total normal force (normal_forces.h).
#pragma once

#include <cmath>

#include "factors/frames.h"
#include "factors/normal_forces.h"
#include "factors/rolling_resistance.h"
#include "factors/traction.h"
#include "factors/ward_state.h"

namespace slipgraph {
namespace ward {

template <typename T>
struct TireForces {
  T f_tire_mps2;       // body-x acceleration from all tire forces, eq. (1)
  T g_tire_radps2;     // yaw acceleration from the driven tires, eq. (2)
  T traction_left_n;   // driven left side traction/braking force
  T traction_right_n;  // driven right side traction/braking force
  T v_rel_left_mps;    // r w_l - v_fwd_l
  T v_rel_right_mps;   // r w_r - v_fwd_r
};

// What the attitude contributes to eqs. (1)-(2): the tires' normal forces (eqs. 3-5) and gravity
// along body x. It depends on the attitude alone, so a filter computes it once per attitude sample
// instead of at every evaluation of the tire forces (the trigonometry was a tenth of an EKF step).
template <typename A>
struct AttitudeLoads {
  A driven_left_n;  // driven wheels of each side (traction, yaw moment)
  A driven_right_n;
  A roll_left_n;  // all wheels of each side (rolling resistance)
  A roll_right_n;
  A gravity_along_x_mps2;  // g sin(phi), phi uphill positive
};

template <typename A>
inline AttitudeLoads<A> ComputeAttitudeLoads(const Attitude<A>& attitude, const Params& p) {
  using std::sin;
  const A roll = WardRollRad(attitude.roll_rad);
  const A phi = WardPitchUphillRad(attitude.pitch_rad);
  const double weight_n = p.mass_kg * p.gravity_mps2;
  AttitudeLoads<A> loads;
  if (p.type == VehicleType::kDiffDriveCastor) {
    const DiffDriveNormalForces<A> n = DiffDriveCastorNormalForcesN(
        weight_n, roll, phi, p.cg_to_front_m, p.cg_to_rear_m, p.track_width_m, p.cg_height_m);
    loads.driven_left_n = n.front_left_n;
    loads.driven_right_n = n.front_right_n;
    loads.roll_left_n = n.front_left_n + n.rear_each_n;
    loads.roll_right_n = n.front_right_n + n.rear_each_n;
  } else {
    const SideNormalForces<A> n =
        SideTotalNormalForcesN(weight_n, roll, phi, p.track_width_m, p.cg_height_m);
    loads.driven_left_n = loads.roll_left_n = n.left_n;
    loads.driven_right_n = loads.roll_right_n = n.right_n;
  }
  loads.gravity_along_x_mps2 = p.gravity_mps2 * sin(phi);
  return loads;
}

// The tire forces with the laws given as functions: traction_n(N, v_rel), eq. (8), and
// rolling_per_n(v_fwd), eq. (9) per newton of load. ComputeTireForces below passes the model's
// laws; identifying the law passes laws whose coefficients are parameter blocks
// (factors/tire_law_coefficients.h).
// T: the state's scalar; A: the attitude's (double when attitude is a measured input, which
// keeps the trigonometry of the normal forces out of the automatic differentiation).
template <typename T, typename A, typename Traction, typename Rolling>
inline TireForces<T> ComputeTireForcesWith(const T* x, const AttitudeLoads<A>& loads,
                                           const Params& p, const Traction& traction_n,
                                           const Rolling& rolling_per_n) {
  const T half_track_yaw = 0.5 * p.track_width_m * x[kYawRate];
  const T v_fwd_left = x[kVbx] - half_track_yaw;
  const T v_fwd_right = x[kVbx] + half_track_yaw;
  const A& driven_left_n = loads.driven_left_n;
  const A& driven_right_n = loads.driven_right_n;
  const A& roll_left_n = loads.roll_left_n;
  const A& roll_right_n = loads.roll_right_n;

  TireForces<T> out;
  out.v_rel_left_mps = TireRelativeVelocityMps(x[kOmegaLeft], p.wheel_radius_m, v_fwd_left);
  out.v_rel_right_mps = TireRelativeVelocityMps(x[kOmegaRight], p.wheel_radius_m, v_fwd_right);
  out.traction_left_n = traction_n(driven_left_n, out.v_rel_left_mps);
  out.traction_right_n = traction_n(driven_right_n, out.v_rel_right_mps);
  // Eq. (9) is linear in N: one evaluation per side serves every wheel on it.
  const T rolling_per_n_left = rolling_per_n(v_fwd_left);
  const T rolling_per_n_right = rolling_per_n(v_fwd_right);
  const T rolling_left_n = roll_left_n * rolling_per_n_left;
  const T rolling_right_n = roll_right_n * rolling_per_n_right;

  out.f_tire_mps2 =
      (out.traction_left_n + out.traction_right_n + rolling_left_n + rolling_right_n) / p.mass_kg;
  // Eq. (2) uses the driven wheels' rolling resistance; for the castor vehicle that is the front
  // pair only (the castors sit near the yaw axis's line and are free to swivel).
  const T yaw_roll_left_n = driven_left_n * rolling_per_n_left;
  const T yaw_roll_right_n = driven_right_n * rolling_per_n_right;
  out.g_tire_radps2 =
      p.track_width_m / (2.0 * p.yaw_inertia_kgm2) *
      (out.traction_right_n + yaw_roll_right_n - out.traction_left_n - yaw_roll_left_n);
  return out;
}

template <typename T, typename A>
inline TireForces<T> ComputeTireForces(const T* x, const AttitudeLoads<A>& loads, const Params& p) {
  return ComputeTireForcesWith(
      x, loads, p, [&p](const A& n, const T& v_rel) { return TractionForceN(n, v_rel, p.tire); },
      [&p](const T& v_fwd) { return RollingResistancePerNewton(v_fwd, p.rolling); });
}

template <typename T, typename A>
inline TireForces<T> ComputeTireForces(const T* x, const Attitude<A>& attitude, const Params& p) {
  return ComputeTireForces(x, ComputeAttitudeLoads(attitude, p), p);
}

// The tires' longitudinal acceleration (m/s^2) on the body held still (v_bx = 0) at state x's
// wheel speeds: minus the disturbance that would just hold the robot (weak constraint 3). At a
// velocity a few cm/s against the wheels the rolling law, steep near v = 0, has turned round,
// so the velocity is set to zero rather than read.
inline double HeldStillTireForce(const double* x, const AttitudeLoads<double>& loads,
                                 const Params& p) {
  double held[kStateSize];
  for (int i = 0; i < kStateSize; ++i) held[i] = x[i];
  held[kVbx] = 0.0;
  return ComputeTireForces(held, loads, p).f_tire_mps2;
}

// Continuous state derivative, eq. (10), noise-free.
template <typename T, typename A>
inline void StateDerivative(const T* x, const AttitudeLoads<A>& loads, const Params& p, T* x_dot) {
  const TireForces<T> forces = ComputeTireForces(x, loads, p);
  x_dot[kVbx] = forces.f_tire_mps2 + x[kAdist] - loads.gravity_along_x_mps2;
  x_dot[kAccelBias] = -x[kAccelBias] / p.accel_bias_tau_s;
  x_dot[kAdist] = T(0.0);
  x_dot[kOmegaLeft] = T(0.0);
  x_dot[kOmegaRight] = T(0.0);
  x_dot[kYawRate] = forces.g_tire_radps2;
  x_dot[kGyroBias] = -x[kGyroBias] / p.gyro_bias_tau_s;
}

template <typename T, typename A>
inline void StateDerivative(const T* x, const Attitude<A>& attitude, const Params& p, T* x_dot) {
  StateDerivative(x, ComputeAttitudeLoads(attitude, p), p, x_dot);
}

// Discrete propagation over dt with classical RK4 on sub-steps no longer than max_substep_s,
// for any continuous derivative `derivative(const T* x, T* x_dot)`.
template <typename T, typename Derivative>
inline void PropagateWith(const T* x, const Derivative& derivative, double dt_s, T* x_next,
                          double max_substep_s = 0.01) {
  const int substeps = dt_s > max_substep_s ? static_cast<int>(std::ceil(dt_s / max_substep_s)) : 1;
  const double h = dt_s / substeps;
  T state[kStateSize], k1[kStateSize], k2[kStateSize], k3[kStateSize], k4[kStateSize],
      tmp[kStateSize];
  for (int i = 0; i < kStateSize; ++i) state[i] = x[i];
  for (int step = 0; step < substeps; ++step) {
    derivative(state, k1);
    for (int i = 0; i < kStateSize; ++i) tmp[i] = state[i] + 0.5 * h * k1[i];
    derivative(tmp, k2);
    for (int i = 0; i < kStateSize; ++i) tmp[i] = state[i] + 0.5 * h * k2[i];
    derivative(tmp, k3);
    for (int i = 0; i < kStateSize; ++i) tmp[i] = state[i] + h * k3[i];
    derivative(tmp, k4);
    for (int i = 0; i < kStateSize; ++i) {
      state[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
  }
  for (int i = 0; i < kStateSize; ++i) x_next[i] = state[i];
}

// Accelerometer-driven form: the white-noise density (squared, (m/s^2)^2 s) of the input
// a_x - g sin(phi): the accelerometer's per-sample noise and the attitude's pitch noise seen
// through gravity, each white over one IMU interval.
inline double AccelInputDensitySq(double sd_accel_mps2, double sd_pitch_rad, double gravity_mps2,
                                  double imu_period_s) {
  const double gravity_noise = gravity_mps2 * sd_pitch_rad;
  return (sd_accel_mps2 * sd_accel_mps2 + gravity_noise * gravity_noise) * imu_period_s;
}

// A first-order Gauss-Markov process of stationary sd `sd` and time constant `tau_s` (the IMU
// biases of eq. 10): the variance its exact discretization adds over dt,
// sd^2 (1 - exp(-2 dt / tau)).
inline double GaussMarkovStepVariance(double sd, double tau_s, double dt_s) {
  return sd * sd * -std::expm1(-2.0 * dt_s / tau_s);
}

// The stationary sd of that process when its driving white noise has density `density`
// (unit / sqrt(s)): density sqrt(tau / 2), the same density over times short against tau.
inline double GaussMarkovStationarySd(double density, double tau_s) {
  return density * std::sqrt(0.5 * tau_s);
}

// Eq. (10) propagated over dt. The tire law is stiff (d v' / d v ~ -g C1 At, about -150 1/s for
// the LAGR values), so forward Euler at 50 Hz diverges; RK4 is stable for |lambda h| < 2.78.
// The EKF and the dynamics factor both call this, so filter and smoother share one
// discretization.
template <typename T, typename A>
inline void Propagate(const T* x, const AttitudeLoads<A>& loads, const Params& p, double dt_s,
                      T* x_next, double max_substep_s = 0.01) {
  PropagateWith(
      x, [&](const T* state, T* x_dot) { StateDerivative(state, loads, p, x_dot); }, dt_s, x_next,
      max_substep_s);
}

template <typename T, typename A>
inline void Propagate(const T* x, const Attitude<A>& attitude, const Params& p, double dt_s,
                      T* x_next, double max_substep_s = 0.01) {
  Propagate(x, ComputeAttitudeLoads(attitude, p), p, dt_s, x_next, max_substep_s);
}

}  // namespace ward
}  // namespace slipgraph
