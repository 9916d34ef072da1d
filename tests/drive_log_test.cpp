// Slicing a log by time and applying a model file's calibration to it (io/drive_log.h).
#include "io/drive_log.h"

#include <gtest/gtest.h>

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

TEST(DriveLog, CalibrationScalesEachSidesWheelsSetsTheTrackAndMovesTheImuStamps) {
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
}

}  // namespace
}  // namespace slipgraph
