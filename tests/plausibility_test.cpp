// Plausibility checks catch wrong mappings on a simulated log with GNSS, turns and rests (the
// bundled hidden-effect log): vibration at rest, rests at different tilts, a z-down IMU, a left
// side that reads backwards, swapped sides, a radius in the wrong unit; the wheels' yaw against the
// gyro's in scale (a track width off, a skid-steer's larger effective track, a gyro in degrees);
// and the clean log passes.
#include "io/plausibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
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
  EXPECT_NEAR(p.figures.wheel_over_gyro_yaw, 1.0, 0.1);
}

TEST(Plausibility, VibrationAtRestIsNotAWrongScale) {
  DriveLog log = Clean();
  std::mt19937 rng(7);
  std::normal_distribution<double> vibration(0.0, 3.0);  // m/s^2, each axis
  for (ImuSample& s : log.imu) {
    s.ax += vibration(rng);
    s.ay += vibration(rng);
    s.az += vibration(rng);
  }
  const Plausibility p = CheckPlausibility(log);
  EXPECT_NEAR(p.figures.rest_norm_mps2, 9.81, 0.3);
  EXPECT_TRUE(p.problems.empty()) << p.problems.front();
}

TEST(Plausibility, RestsAtDifferentTiltsKeepTheirGravity) {
  // The log's rest at the start parked 25 deg nose-up, a second rest (40-45 s, wheels stopped)
  // 25 deg nose-down: one mean over both would read about 9.0 m/s^2.
  DriveLog log = Clean();
  const double g = 9.81, tilt = 25.0 * M_PI / 180.0;
  for (WheelSample& w : log.wheels) {
    if (w.t >= 40.0 && w.t <= 45.0) w.omega_radps.fill(0.0);
  }
  for (ImuSample& s : log.imu) {
    const bool first = s.t < 3.0, second = s.t >= 40.0 && s.t <= 45.0;
    if (!first && !second) continue;
    s.ax = (first ? 1.0 : -1.0) * g * std::sin(tilt);
    s.ay = 0.0;
    s.az = g * std::cos(tilt);
  }
  const Plausibility p = CheckPlausibility(log);
  ASSERT_TRUE(p.figures.gravity_at_rest);
  EXPECT_GT(p.figures.rest_seconds, 6.0);  // both rests
  EXPECT_NEAR(p.figures.rest_norm_mps2, g, 0.05);
  EXPECT_TRUE(p.problems.empty()) << p.problems.front();
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

TEST(Plausibility, TrackWidthHalfTheTrueOnADifferentialDrive) {
  DriveLog log = Clean();
  log.vehicle.track_width_m *= 0.5;  // the wheels then imply twice the yaw the body makes
  const Plausibility p = CheckPlausibility(log);
  EXPECT_NEAR(p.figures.wheel_over_gyro_yaw, 2.0, 0.2);
  EXPECT_TRUE(Mentions(p, "track_width too small")) << p.problems.size();
}

TEST(Plausibility, TrackWidthTwiceTheTrueOnADifferentialDrive) {
  DriveLog log = Clean();
  log.vehicle.track_width_m *= 2.0;  // the wheels then imply half the yaw the body makes
  const Plausibility p = CheckPlausibility(log);
  EXPECT_NEAR(p.figures.wheel_over_gyro_yaw, 0.5, 0.05);
  EXPECT_TRUE(Mentions(p, "track_width too large")) << p.problems.size();
}

TEST(Plausibility, ASkidSteersWheelsMayImplyMoreYawThanTheBodyMakes) {
  DriveLog log = Clean();
  log.vehicle.type = VehicleType::kSkidSteer;
  log.vehicle.track_width_m *= 0.5;  // an effective track twice the geometric one
  const Plausibility p = CheckPlausibility(log);
  EXPECT_NEAR(p.figures.wheel_over_gyro_yaw, 2.0, 0.2);
  EXPECT_TRUE(p.problems.empty()) << p.problems.front();
}

TEST(Plausibility, ASkidSteersWheelsBeyondAnySkid) {
  DriveLog log = Clean();
  log.vehicle.type = VehicleType::kSkidSteer;
  log.vehicle.track_width_m *= 0.1;  // ten times the yaw
  const Plausibility p = CheckPlausibility(log);
  EXPECT_NEAR(p.figures.wheel_over_gyro_yaw, 10.0, 1.0);
  EXPECT_TRUE(Mentions(p, "rad/s converted as if deg/s")) << p.problems.size();
}

TEST(Plausibility, GyroInDegreesPerSecond) {
  DriveLog log = Clean();
  for (ImuSample& s : log.imu) s.gz *= 180.0 / M_PI;
  const Plausibility p = CheckPlausibility(log);
  EXPECT_NEAR(p.figures.wheel_over_gyro_yaw, M_PI / 180.0, 0.002);
  EXPECT_TRUE(Mentions(p, "deg/s read as rad/s")) << p.problems.size();
}

TEST(Plausibility, ATurnWithinTheGyrosNoiseGivesNoScale) {
  DriveLog log = Clean();
  for (ImuSample& s : log.imu) s.gz *= 0.15;  // the gyro's rate varies by about 0.035 rad/s
  const Plausibility p = CheckPlausibility(log);
  EXPECT_GT(p.figures.wheel_gyro_yaw_correlation, 0.5);
  EXPECT_TRUE(std::isnan(p.figures.wheel_over_gyro_yaw));
}

TEST(Plausibility, TheFiguresInOneLine) {
  PlausibilityFigures f;
  EXPECT_EQ(DescribePlausibility(f), "");
  f.gravity_at_rest = true, f.rest_seconds = 4.0, f.rest_norm_mps2 = 9.8;
  f.wheel_gyro_yaw_correlation = 0.9, f.wheel_over_gyro_yaw = 1.2;
  EXPECT_EQ(DescribePlausibility(f),
            "gravity at rest 9.8 m/s^2 over 4 s; wheels' yaw rate 1.2 x the gyro's (correlation "
            "0.9)");
  f.gravity_at_rest = false;
  EXPECT_NE(DescribePlausibility(f).find("gravity over the whole log"), std::string::npos);
}

}  // namespace
}  // namespace slipgraph
