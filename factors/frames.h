// Frame and sign conventions shared by the physics.
//
// Logs use REP-103: body x forward, y left, z up; roll about x, pitch about y with positive pitch
// = nose DOWN; yaw counter-clockwise. Ward & Iagnemma's phi is the pitch with uphill (nose UP)
// positive, and their theta the roll with the right side down positive (the same sense as REP-103
// roll). Convert here, explicitly, never silently.
#pragma once

#include <cmath>

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

// A GNSS velocity (world east, north, up) along the body's x axis, eq. (11)'s measurement: its
// dot product with x_body = (cos yaw cos pitch, sin yaw cos pitch, -sin pitch) at a REP-103
// attitude. Without an attitude the horizontal speed, signed by the direction the wheels drive
// (the sign of the left and right wheel speeds' sum; forward at 0).
inline double GnssVelocityAlongBodyX(double ve, double vn, double vu, bool have_attitude,
                                     double pitch_rad, double yaw_rad, double wheel_speed_sum) {
  if (!have_attitude) return (wheel_speed_sum >= 0.0 ? 1.0 : -1.0) * std::hypot(ve, vn);
  const double cp = std::cos(pitch_rad);
  return ve * std::cos(yaw_rad) * cp + vn * std::sin(yaw_rad) * cp - vu * std::sin(pitch_rad);
}

}  // namespace slipgraph
