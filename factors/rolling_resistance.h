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

template <typename T>
inline T RollingResistanceForceN(const T& normal_force_n, const T& v_fwd_mps,
                                 const RollingParams& rolling) {
  return -normal_force_n *
         (rolling.R1 * SignedSaturation(v_fwd_mps, rolling.A_roll) + rolling.R2 * v_fwd_mps);
}

}  // namespace slipgraph
