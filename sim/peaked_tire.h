// Truth physics the estimators do not contain (the mismatch suites, docs/mismatch.md): traction
// from the longitudinal slip ratio with a peak and a falling branch (Pacejka's "magic formula"
// in its longitudinal form), built up over a relaxation length, and a rolling resistance
// linear in speed. Ward & Iagnemma's eq. (8) and (9), which every estimator uses, are laws of
// the slip velocity that rise monotonically; this one is another family: at a given slip
// velocity it pulls harder the slower the robot goes, and it falls once the wheel spins.
//
//   kappa_ss = v_rel / max(|r w|, |v_fwd|, v_floor)            (steady-state slip ratio)
//   d kappa / dt = (max(|v_fwd|, |r w|) + v_floor) / L (kappa_ss - kappa)
//                                                               (relaxation over length L of
//                                                               tread or ground passing)
//   F = N D sin(C atan(B kappa - E (B kappa - atan(B kappa))))  (traction, N)
//   F_roll = -N (c0 + c1 |v_fwd|) tanh(v_fwd / v_floor)         (rolling resistance, N)
//
// v_rel = r w - v_fwd (m/s), N the wheel's normal force (N). Only the simulator uses it.
#pragma once

#include <algorithm>
#include <cmath>

namespace slipgraph {
namespace sim {

struct PeakedSoil {
  double peak_mu = 0.6;       // D: the friction coefficient at the peak
  double stiffness_b = 8.0;   // B
  double shape_c = 1.5;       // C (> 1: the force falls beyond the peak)
  double curvature_e = 0.0;   // E
  double roll_c0 = 0.05;      // rolling resistance coefficient at rest
  double roll_c1_spm = 0.02;  // its growth with speed, s/m
};

// Speeds below this are regularized (m/s): the slip ratio stays finite at rest.
constexpr double kPeakedSpeedFloorMps = 0.05;

inline double SteadySlipRatio(double surface_speed_mps, double v_fwd_mps) {
  const double v_rel = surface_speed_mps - v_fwd_mps;
  const double scale =
      std::max({std::abs(surface_speed_mps), std::abs(v_fwd_mps), kPeakedSpeedFloorMps});
  return v_rel / scale;
}

// One explicit step of the slip ratio's relaxation toward kappa_ss over length_m of tread or
// ground passing the contact (a wheel spinning in place builds its slip as fast as one rolling).
// The step never overshoots (at most the whole way), so it is stable at any dt.
inline double RelaxSlipRatio(double kappa, double kappa_ss, double v_fwd_mps,
                             double surface_speed_mps, double length_m, double dt_s) {
  const double speed = std::max(std::abs(v_fwd_mps), std::abs(surface_speed_mps));
  const double rate = (speed + kPeakedSpeedFloorMps) / length_m;
  return kappa + std::min(1.0, rate * dt_s) * (kappa_ss - kappa);
}

inline double PeakedTractionForceN(double normal_n, double kappa, const PeakedSoil& soil) {
  const double bk = soil.stiffness_b * kappa;
  return normal_n * soil.peak_mu *
         std::sin(soil.shape_c * std::atan(bk - soil.curvature_e * (bk - std::atan(bk))));
}

// Rolling resistance linear in speed, -N (c0 + c1 |v|), its sign smoothed over
// kPeakedSpeedFloorMps (the mismatch suites' wheels and tracks alike).
inline double RollingResistanceN(double normal_n, double v_fwd_mps, double c0, double c1_spm) {
  return -normal_n * (c0 + c1_spm * std::abs(v_fwd_mps)) *
         std::tanh(v_fwd_mps / kPeakedSpeedFloorMps);
}

inline double PeakedRollingForceN(double normal_n, double v_fwd_mps, const PeakedSoil& soil) {
  return RollingResistanceN(normal_n, v_fwd_mps, soil.roll_c0, soil.roll_c1_spm);
}

}  // namespace sim
}  // namespace slipgraph
