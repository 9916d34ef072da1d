// Tire traction / braking force, Ward & Iagnemma eq. (8):
//
//   F_traction = N ( sign(v_rel) C1 (1 - exp(-At |v_rel|)) + C2 v_rel ),   v_rel = r w - v_fwd
//
// Inputs: N normal force on the tire (N), v_rel tire surface speed relative to the ground (m/s),
// positive when the wheel spins faster than the ground moves under it (traction), negative when
// braking. Output: force along the wheel's heading (N), positive forward. Continuous and
// differentiable everywhere, including v_rel = 0 (see smooth_math.h).
#pragma once

#include <cmath>

#include "factors/smooth_math.h"
#include "model/vehicle.h"

namespace slipgraph {

// Eq. (8) with coefficients of any scalar S (a Ceres parameter block when the law is identified,
// factors/tire_law_coefficients.h). The rate At enters through the saturation's argument,
// sgn(v)(1 - exp(-At |v|)) = sat(v At / At_ref; At_ref) for any positive constant At_ref, so the
// saturation keeps its one-exp Jet path; with At_ref = At the argument is v exactly.
template <typename N, typename T, typename S>
inline T TractionForceOf(const N& normal_force_n, const T& v_rel_mps, const S& c1, const S& at,
                         const S& c2, double at_reference) {
  return normal_force_n *
         (c1 * SignedSaturation(v_rel_mps * (at / at_reference), at_reference) + c2 * v_rel_mps);
}

// N and T may differ (e.g. a double normal force from measured attitude and a Jet velocity).
template <typename N, typename T>
inline T TractionForceN(const N& normal_force_n, const T& v_rel_mps, const TireParams& tire) {
  return TractionForceOf(normal_force_n, v_rel_mps, tire.C1, tire.At, tire.C2, tire.At);
}

// The slip speed v_rel in (0, up_to_mps] at which eq. (8)'s traction changes sign (a falling
// branch, C2 < 0, that outweighs the saturated C1), or NaN where it keeps its sign up to there.
// For v_rel > 0 the law is concave through zero, so its sign at up_to_mps decides and bisection
// finds the change; the law is odd, so braking reverses at the same speed.
inline double TractionReversalSpeedMps(const TireParams& tire, double up_to_mps) {
  const auto force = [&](double v_rel) { return TractionForceN(1.0, v_rel, tire); };
  if (!(up_to_mps > 0.0) || !(force(up_to_mps) <= 0.0)) return std::nan("");
  double low = 0.0, high = up_to_mps;
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (low + high);
    (force(middle) > 0.0 ? low : high) = middle;
  }
  return high;
}

// Relative velocity of a tire, v_rel = r w - v_fwd (Ward & Iagnemma, below eq. 8).
template <typename T>
inline T TireRelativeVelocityMps(const T& omega_radps, double wheel_radius_m, const T& v_fwd_mps) {
  return wheel_radius_m * omega_radps - v_fwd_mps;
}

}  // namespace slipgraph
