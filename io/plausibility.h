// Plausibility checks on a log's streams, for imported logs above all: a wrong mapping (a
// flipped axis, a wheel side with the wrong sign, swapped sides, wrong units) shows as a physical
// impossibility. Each finding says what looks wrong and what would explain it. Run by
// `slipgraph info` (through log_summary).
//
// - gravity at rest: the mean specific force while the wheels stand still (over the whole log
//   when they never do) is about g along +z (REP-103, z up); -g means a z-down IMU frame;
// - wheels against GNSS: while GNSS shows the robot moving, the mean wheel surface speed should
//   be comparable to the GNSS speed (slip makes it larger, never near zero or negative when the
//   robot drives forward); a side that reads backwards cancels the other;
// - wheels against the gyro: the yaw rate the wheel speeds imply, r (w_r - w_l) / track, should
//   rise and fall with the gyro's z rate; anticorrelation means swapped sides (or a flipped gyro).
//   Its scale too, where the two fit closely: on a differential drive with castors about the
//   gyro's (0.7-1.4 x), on any other drive (skid_steer, rocker_bogie6) larger (the wheels skid
//   in a turn) but not below 0.7 x nor beyond 6 x; outside, the track width, the wheel radius or
//   the gyro's unit is wrong. Wheel speeds made from a controller's odometry twist carry its
//   yaw instead (io/ros_log_builder.h: the wheel-separation multiplier).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

struct PlausibilityFigures {
  double rest_seconds = 0.0;  // time with every wheel still (the gravity check's data)
  // Gravity's figures below come from the still stretches; false: the log is never still, and
  // they come from the whole log.
  bool gravity_at_rest = false;
  double rest_az_mps2 = std::nan("");
  double rest_norm_mps2 = std::nan("");
  double wheel_over_gnss_speed = std::nan("");  // median ratio while moving
  double wheel_gyro_yaw_correlation = std::nan("");
  // The slope of the wheels' yaw rate on the gyro's (each wheel cycle against the gyro's mean
  // over it), where the robot turned and the two correlate (NaN otherwise): about 1 on a
  // differential drive, above 1 on a skid-steer, whose effective track is this times
  // track_width. Scatter pulls it towards 0 by up to the squared correlation.
  double wheel_over_gyro_yaw = std::nan("");
};

struct Plausibility {
  PlausibilityFigures figures;
  std::vector<std::string> problems;
};

Plausibility CheckPlausibility(const DriveLog& log);

// The figures in one line ("gravity at rest 9.81 m/s^2 over 12 s; wheels' speed 1.02 x GNSS's;
// wheels' yaw rate 0.99 x the gyro's (correlation 0.97)"), each only where it was measured; empty
// when none was.
std::string DescribePlausibility(const PlausibilityFigures& figures);

}  // namespace slipgraph
