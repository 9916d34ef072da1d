// Frame and sign conventions shared by the physics.
//
// Logs use REP-103: body x forward, y left, z up; roll about x, pitch about y with positive pitch
// = nose DOWN; yaw counter-clockwise. Ward & Iagnemma's phi is the pitch with uphill (nose UP)
// positive, and their theta the roll with the right side down positive (the same sense as REP-103
// roll). Convert here, explicitly, never silently.
#pragma once

namespace slipgraph {

// Ward's phi (uphill positive) from a REP-103 pitch (nose down positive).
template <typename T>
inline T WardPitchUphillRad(const T& pitch_rep103_rad) {
  return -pitch_rep103_rad;
}

// Ward's theta (right side down positive) from a REP-103 roll: the same sense.
template <typename T>
inline T WardRollRad(const T& roll_rep103_rad) {
  return roll_rep103_rad;
}

}  // namespace slipgraph
