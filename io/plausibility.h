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
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

struct PlausibilityFigures {
  double rest_seconds = 0.0;  // time with every wheel still (the gravity check's data)
  double rest_az_mps2 = std::nan("");
  double rest_norm_mps2 = std::nan("");
  double wheel_over_gnss_speed = std::nan("");  // median ratio while moving
  double wheel_gyro_yaw_correlation = std::nan("");
};

struct Plausibility {
  PlausibilityFigures figures;
  std::vector<std::string> problems;
};

Plausibility CheckPlausibility(const DriveLog& log);

}  // namespace slipgraph
