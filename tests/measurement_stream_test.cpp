#include "io/measurement_stream.h"

#include <gtest/gtest.h>

namespace slipgraph {
namespace {

TEST(MeasurementStream, MergesInTimeOrderWithFixedTieOrder) {
  DriveLog log;
  log.imu = {{0.0}, {0.01}, {0.02}};
  log.wheels.resize(2);
  log.wheels[0].t = 0.005;
  log.wheels[1].t = 0.02;  // tie with imu[2]: IMU first
  log.gps = {GpsSample{}};
  log.gps[0].t = 0.01;  // tie with imu[1]
  const std::vector<StreamEntry> merged = MergeStreams(log);
  ASSERT_EQ(merged.size(), 6u);
  const Stream expected[] = {Stream::kImu, Stream::kWheels, Stream::kImu,
                             Stream::kGps, Stream::kImu,    Stream::kWheels};
  for (size_t i = 0; i < merged.size(); ++i) {
    EXPECT_EQ(merged[i].stream, expected[i]) << i;
    if (i > 0) {
      EXPECT_LE(merged[i - 1].t, merged[i].t);
    }
  }
  EXPECT_EQ(merged[4].index, 2);
}

TEST(MeasurementStream, AStreamOutOfOrderIsStillMergedInTimeOrder) {
  // The sorted runs are merged; a run out of order falls back to a stable sort of everything.
  DriveLog log;
  log.imu = {{0.02}, {0.0}, {0.01}};
  log.wheels.resize(1);
  log.wheels[0].t = 0.01;  // tie with imu[2]: IMU first
  const std::vector<StreamEntry> merged = MergeStreams(log);
  ASSERT_EQ(merged.size(), 4u);
  const int imu_order[] = {1, 2, -1, 0};
  for (size_t i = 0; i < merged.size(); ++i) {
    if (i > 0) {
      EXPECT_LE(merged[i - 1].t, merged[i].t);
    }
    if (imu_order[i] >= 0) {
      EXPECT_EQ(merged[i].stream, Stream::kImu) << i;
      EXPECT_EQ(merged[i].index, imu_order[i]) << i;
    } else {
      EXPECT_EQ(merged[i].stream, Stream::kWheels) << i;
    }
  }
}

TEST(MeasurementStream, SelectionLeavesOutStreams) {
  DriveLog log;
  log.imu = {{0.0}};
  log.gps.resize(3);
  StreamSelection no_gps;
  no_gps.Set(Stream::kGps, false);
  EXPECT_EQ(MergeStreams(log, no_gps).size(), 1u);
  EXPECT_STREQ(StreamName(Stream::kArticulation), "articulation");
}

TEST(MeasurementStream, RockerBogieSidesAreMeansOfThreeWheels) {
  WheelSample w;
  w.omega_radps = {1.0, 2.0, 3.0, 4.0, 5.0, 9.0};
  const SideSpeeds rocker = DrivenSideSpeeds(w, VehicleType::kRockerBogie6);
  EXPECT_DOUBLE_EQ(rocker.left_radps, 2.0);
  EXPECT_DOUBLE_EQ(rocker.right_radps, 6.0);
  const SideSpeeds diff = DrivenSideSpeeds(w, VehicleType::kDiffDriveCastor);
  EXPECT_DOUBLE_EQ(diff.left_radps, 1.0);
  EXPECT_DOUBLE_EQ(diff.right_radps, 2.0);
}

}  // namespace
}  // namespace slipgraph
