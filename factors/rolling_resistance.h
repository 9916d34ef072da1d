// Rolling resistance, Ward & Iagnemma eq. (9):
//
//   F_roll = -sign(v_fwd) N ( R1 (1 - exp(-A_roll |v_fwd|)) + R2 |v_fwd| )
//          = -N ( R1 sign(v_fwd) (1 - exp(-A_roll |v_fwd|)) + R2 v_fwd )
//
// Inputs: N normal force (N), v_fwd forward speed of the tire's centre over ground (m/s).
// Output: force along the wheel's heading (N), opposing motion. sign(v)|v| = v makes the viscous
// part linear; the static part is smooth at v_fwd = 0 (see smooth_math.h).
#pragma once

#include "factors/smooth_math.h"
#include "model/vehicle.h"

namespace slipgraph {

// The force per newton of normal load, -(R1 sign(v)(1 - exp(-A_roll |v|)) + R2 v): the law is
// linear in N, so wheels sharing a forward speed share this factor.
// R1 and R2 of any scalar S (a Ceres parameter block when the law is identified); A_roll a
// constant.
template <typename T, typename S>
inline T RollingResistancePerNewtonOf(const T& v_fwd_mps, const S& r1, double a_roll, const S& r2) {
  return -(r1 * SignedSaturation(v_fwd_mps, a_roll) + r2 * v_fwd_mps);
}

template <typename T>
inline T RollingResistancePerNewton(const T& v_fwd_mps, const RollingParams& rolling) {
  return RollingResistancePerNewtonOf(v_fwd_mps, rolling.R1, rolling.A_roll, rolling.R2);
}

// N and T may differ (e.g. a double normal force from measured attitude and a Jet velocity).
template <typename N, typename T>
inline T RollingResistanceForceN(const N& normal_force_n, const T& v_fwd_mps,
                                 const RollingParams& rolling) {
  return normal_force_n * RollingResistancePerNewton(v_fwd_mps, rolling);
}

}  // namespace slipgraph
