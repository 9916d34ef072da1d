// Truth physics of the tracked robot in the mismatch suite ipd35m (docs/mismatch.md): the soil's
// shear under each track integrated over its contact, as in Wong's theory of skid-steering
// (Theory of Ground Vehicles, ch. 2 and 7). Rogers-Marcovitz et al.'s slip model, which IPD
// identifies, is linear in 13 features of the velocity and gravity; this one is not: a track's
// slip grows without bound as its thrust nears the soil's strength, the strength depends on the
// load the track carries (cohesion plus friction), and in a turn the tracks slide sideways, which
// takes the soil's shear away from the thrust.
//
// A point of track i at x along its contact (length L, x forward, entering at the front when the
// belt runs forward) slides over the ground at s = (-(r w_i - v_i), v_y + w x), v_i = V_x -/+ B/2
// V_yaw the ground speed of the track's line (left, right). Its shear displacement j is what it
// has slid since it entered (the length of the integral of s over its time in the contact), and
// the soil's shear stress opposes the sliding s with Janosi-Hanamoto's magnitude
//
//   tau = (c + p tan(phi)) (1 - exp(-j / K)),   p = W_i / (b L)
//
// (b the belt's width, W_i the track's load, moved to the outer track by the sideways specific
// force v w - g_y at the centre of gravity's height). The body follows the shear's resultant
// forces and moment, rolling resistance W (c_r0 + c_r1 |v|) tanh(v / 0.05 m/s) and gravity (only
// the simulator uses this).
#pragma once

#include <algorithm>
#include <cmath>

namespace slipgraph {
namespace sim {

struct TrackSoil {
  double cohesion_pa = 2000.0;      // c
  double friction_angle_rad = 0.5;  // phi
  double shear_modulus_m = 0.02;    // K, Janosi-Hanamoto's shear deformation modulus
  double roll_c0 = 0.04;            // rolling (motion) resistance coefficient
  double roll_c1_spm = 0.01;        // its growth with speed, s/m
};

// The tracks' contact, fixed for the robot.
struct TrackGeometry {
  double contact_length_m = 0.7;  // L
  double belt_width_m = 0.2;      // b
};

// Below this speed the belt's time in the contact is regularized (m/s).
constexpr double kTrackSpeedFloorMps = 0.05;
// Sliding speeds below this turn the shear's direction smoothly (m/s); the thrust of a track
// slipping at s is s / sqrt(s^2 + floor^2) of Janosi-Hanamoto's.
constexpr double kTrackSlideFloorMps = 0.001;
// Points along each contact at which the shear is integrated (midpoint rule).
constexpr int kTrackContactPoints = 12;

// Janosi-Hanamoto's thrust of a track going straight, as a share of its strength over the
// contact, at shear displacement x = j / K at its rear: 1 - (1 - e^-x) / x (what TrackShear
// integrates when nothing slides sideways).
inline double ShearShare(double x) {
  if (x < 1e-6) return x * (0.5 - x / 6.0);  // its series, where the closed form cancels
  return 1.0 - -std::expm1(-x) / x;
}

// Resultant of the soil's shear on one track, in body axes: force along x and y (N) and the
// moment about the track's centre (N m, counter-clockwise).
struct TrackForce {
  double x_n = 0.0;
  double y_n = 0.0;
  double moment_nm = 0.0;
};

// One track whose belt runs at `tread_mps` over ground it crosses at `ground_mps` (its line's
// speed along x), the body sliding sideways at `v_y_mps` and turning at `yaw_rate_radps`;
// `strength_pa` = c + p tan(phi).
inline TrackForce TrackShear(double tread_mps, double ground_mps, double v_y_mps,
                             double yaw_rate_radps, double strength_pa, double shear_modulus_m,
                             const TrackGeometry& track) {
  const double length = track.contact_length_m;
  const double slip = tread_mps - ground_mps;  // the belt runs ahead of the ground by this
  const double belt = std::max(std::abs(tread_mps), kTrackSpeedFloorMps);
  const double dx = length / kTrackContactPoints;
  TrackForce force;
  for (int k = 0; k < kTrackContactPoints; ++k) {
    const double x = -0.5 * length + (k + 0.5) * dx;
    // What the point has slid over the ground since it entered the contact: back by the belt's
    // slip over the time it has been in, sideways by v_y + w x' over the positions x' it passed.
    const double entry = tread_mps >= 0.0 ? 0.5 * length : -0.5 * length;
    const double d_x = -slip * std::abs(entry - x) / belt;
    const double d_y = (v_y_mps * (entry - x) + 0.5 * yaw_rate_radps * (entry * entry - x * x)) /
                       (tread_mps >= 0.0 ? belt : -belt);
    const double j = std::hypot(d_x, d_y);
    // The soil opposes the point's sliding over the ground, s = (-slip, v_y + w x), its
    // direction regularized over kTrackSlideFloorMps (a point whose sliding reverses turns its
    // shear over a millimetre per second, not at once).
    const double s_x = -slip, s_y = v_y_mps + yaw_rate_radps * x;
    const double s = std::sqrt(s_x * s_x + s_y * s_y + kTrackSlideFloorMps * kTrackSlideFloorMps);
    const double tau = strength_pa * -std::expm1(-j / shear_modulus_m) * track.belt_width_m * dx;
    force.x_n -= tau * s_x / s;  // thrust forward when the belt runs ahead
    force.y_n -= tau * s_y / s;
    force.moment_nm -= tau * s_y / s * x;
  }
  return force;
}

}  // namespace sim
}  // namespace slipgraph
