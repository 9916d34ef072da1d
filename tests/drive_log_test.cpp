// Slicing a log by time and applying a model file's calibration to it (io/drive_log.h).
#include "io/drive_log.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slipgraph {
namespace {

DriveLog TwoWheelLog() {
  DriveLog log;
  log.vehicle.type = VehicleType::kDiffDriveCastor;
  log.vehicle.track_width_m = 0.55;
  for (int i = 0; i < 10; ++i) {
    WheelSample w;
    w.t = i;
    w.omega_radps[0] = 2.0;  // left
    w.omega_radps[1] = 4.0;  // right
    log.wheels.push_back(w);
    ImuSample imu;
    imu.t = i + 0.5;
    log.imu.push_back(imu);
  }
  log.events.push_back({2.5, 6.5, "held"});
  log.events.push_back({8.0, 9.0, "late"});
  return log;
}

TEST(DriveLog, SliceKeepsTheSamplesInItsRangeAndClipsTheEvents) {
  const DriveLog slice = SliceLog(TwoWheelLog(), 3.0, 7.0);
  ASSERT_EQ(slice.wheels.size(), 4u);  // t = 3, 4, 5, 6
  EXPECT_EQ(slice.wheels.front().t, 3.0);
  EXPECT_EQ(slice.wheels.back().t, 6.0);
  ASSERT_EQ(slice.imu.size(), 4u);  // 3.5 .. 6.5
  ASSERT_EQ(slice.events.size(), 1u);
  EXPECT_EQ(slice.events[0].t_start, 3.0);
  EXPECT_EQ(slice.events[0].t_end, 6.5);
  EXPECT_EQ(slice.vehicle.track_width_m, 0.55);
}

TEST(DriveLog, CalibrationScalesEachSidesWheelsSetsTheTrackAndMovesTheStamps) {
  DriveLog log = TwoWheelLog();
  ModelConfig model;
  ApplyCalibration(model, &log);  // the default changes nothing
  EXPECT_EQ(log.wheels[0].omega_radps[0], 2.0);
  EXPECT_EQ(log.vehicle.track_width_m, 0.55);
  model.calibration.wheel_radius_scale_left = 1.05;
  model.calibration.wheel_radius_scale_right = 0.9;
  model.calibration.track_width_m = 0.8;
  model.calibration.imu_time_offset_s = 0.05;  // the IMU's stamps late by 50 ms
  ApplyCalibration(model, &log);
  EXPECT_DOUBLE_EQ(log.wheels[3].omega_radps[0], 2.1);
  EXPECT_DOUBLE_EQ(log.wheels[3].omega_radps[1], 3.6);
  EXPECT_EQ(log.vehicle.track_width_m, 0.8);
  EXPECT_DOUBLE_EQ(log.imu[3].t, 3.45);
  EXPECT_EQ(log.wheels[3].t, 3.0);
  ModelConfig late_wheels;
  late_wheels.calibration.wheels_time_offset_s = 0.36;  // the encoders' stamps late by 360 ms
  ApplyCalibration(late_wheels, &log);
  EXPECT_DOUBLE_EQ(log.wheels[3].t, 2.64);
  EXPECT_DOUBLE_EQ(log.imu[3].t, 3.45);
}

TEST(DriveLog, CalibrationRotatesAPitchedImuBackOntoTheBody) {
  // The body's specific force and rate, seen by an IMU pitched nose-down by 0.1 rad about body
  // y as sim/sensor_models.cpp pitches it: x' = x cos d - z sin d, z' = x sin d + z cos d.
  const double d = 0.1, fx = 0.4, fz = 9.81, wx = 0.05, wz = 0.3;
  DriveLog log = TwoWheelLog();
  for (ImuSample& s : log.imu) {
    s.ax = fx * std::cos(d) - fz * std::sin(d), s.az = fx * std::sin(d) + fz * std::cos(d);
    s.gx = wx * std::cos(d) - wz * std::sin(d), s.gz = wx * std::sin(d) + wz * std::cos(d);
    s.ay = 0.2, s.gy = 0.01;
  }
  ModelConfig model;
  model.calibration.imu_mounting_pitch_rad = d;
  ApplyCalibration(model, &log);
  for (const ImuSample& s : log.imu) {
    EXPECT_NEAR(s.ax, fx, 1e-12);
    EXPECT_NEAR(s.az, fz, 1e-12);
    EXPECT_NEAR(s.gx, wx, 1e-12);
    EXPECT_NEAR(s.gz, wz, 1e-12);
    EXPECT_EQ(s.ay, 0.2);  // about y: y unchanged
    EXPECT_EQ(s.gy, 0.01);
  }
}

}  // namespace
}  // namespace slipgraph
