// Longitudinal wheel slip, Ward & Iagnemma eqs. (6)-(7), as one bounded expression:
//
//   slip = (r w - v_fwd) / max(|r w|, |v_fwd|)
//
// which is the slip i = 1 - v_fwd / (r w) while driving (r w >= v_fwd >= 0), minus the skid
// i_s = 1 - r w / v_fwd while braking (v_fwd > r w >= 0), 1 when the wheel spins and the body
// stands still, and 0 when both are (nearly) zero. Used for truth, the detector and estimates.
#pragma once

#include <algorithm>
#include <cmath>

namespace slipgraph {

// Speeds below this (m/s) count as zero: slip is undefined there and reported as 0.
constexpr double kSlipSpeedFloorMps = 1e-3;

inline double SlipRatio(double surface_speed_mps, double v_fwd_mps) {
  const double scale =
      std::max({std::abs(surface_speed_mps), std::abs(v_fwd_mps), kSlipSpeedFloorMps});
  return (surface_speed_mps - v_fwd_mps) / scale;
}

}  // namespace slipgraph
