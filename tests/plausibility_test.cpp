// Plausibility checks catch wrong mappings on a simulated log with GNSS, turns and rests (the
// bundled hidden-effect log): a z-down IMU, a left side that reads backwards, swapped sides, a
// radius in the wrong unit; and the clean log passes.
#include "io/plausibility.h"

#include <gtest/gtest.h>

#include <string>

#include "io/log_reader.h"
#include "tests/import_test_util.h"

namespace slipgraph {
namespace {

DriveLog Clean() {
  return ReadDriveLog(std::string(SLIPGRAPH_DATA_DIR) + "/hidden_quadratic_drag");
}

using testing::Mentions;

TEST(Plausibility, CleanLogPasses) {
  const Plausibility p = CheckPlausibility(Clean());
  EXPECT_TRUE(p.problems.empty()) << p.problems.front();
  EXPECT_GT(p.figures.rest_seconds, 1.0);
  EXPECT_NEAR(p.figures.rest_az_mps2, 9.81, 0.3);
  EXPECT_GT(p.figures.wheel_over_gnss_speed, 0.8);
  EXPECT_GT(p.figures.wheel_gyro_yaw_correlation, 0.8);
}

TEST(Plausibility, FlippedImuZ) {
  DriveLog log = Clean();
  for (ImuSample& s : log.imu) s.az = -s.az, s.ay = -s.ay, s.gz = -s.gz, s.gy = -s.gy;
  const Plausibility p = CheckPlausibility(log);
  EXPECT_TRUE(Mentions(p, "z axis points down"));
}

TEST(Plausibility, LeftWheelsNegativeForward) {
  DriveLog log = Clean();
  for (WheelSample& w : log.wheels) w.omega_radps[0] = -w.omega_radps[0];
  const Plausibility p = CheckPlausibility(log);
  EXPECT_TRUE(Mentions(p, "one side reads backwards")) << p.problems.size();
}

TEST(Plausibility, SwappedWheelSides) {
  DriveLog log = Clean();
  for (WheelSample& w : log.wheels) std::swap(w.omega_radps[0], w.omega_radps[1]);
  const Plausibility p = CheckPlausibility(log);
  EXPECT_TRUE(Mentions(p, "left and right wheels swapped"));
}

TEST(Plausibility, WheelRadiusInTheWrongUnit) {
  DriveLog log = Clean();
  log.vehicle.wheel_radius_m *= 100.0;  // centimetres given as metres
  const Plausibility p = CheckPlausibility(log);
  EXPECT_TRUE(Mentions(p, "radius or units wrong"));
}

}  // namespace
}  // namespace slipgraph
