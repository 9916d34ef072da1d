#include "io/log_writer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/log_reader.h"
#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

// Bit-exact comparison that treats NaN == NaN.
bool Same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

DriveLog MakeRockerLog() {
  DriveLog log;
  Vehicle& v = log.vehicle;
  v.name = "rover";
  v.type = VehicleType::kRockerBogie6;
  v.mass_kg = 10.5, v.yaw_inertia_kgm2 = 0.8, v.wheel_radius_m = 0.065;
  v.track_width_m = 0.4, v.cg_height_m = 0.2, v.axle_spacing_m = 0.17;
  v.tire = {0.6, 15.0, -0.01};
  v.rolling = {0.05, 25.0, 0.02};
  for (int k = 0; k < 5; ++k) {
    const double t = 0.1 * k + 1.0 / 3.0;  // awkward binary fractions on purpose
    log.imu.push_back({t, 0.1 * k, -0.2, 9.81 + 1e-9 * k, 0.0, 1e-4, -0.3});
    WheelSample w;
    w.t = t;
    for (int i = 0; i < 6; ++i) w.omega_radps[i] = 0.5 + 0.01 * i + k;
    log.wheels.push_back(w);
    log.attitude.push_back({t, 0.01, -0.02, 1.5, 0.001, kMissing, 0.01});
    log.commands.push_back({t, 0.05, 0.0});
    log.articulation.push_back({t, Side::kLeft, 0.003, -0.004});
    log.articulation.push_back({t, Side::kRight, 0.001, 0.002});
    log.range.push_back({t, Side::kLeft, 0.5, 0.01});
    log.range.push_back({t, Side::kLeft, 0.6, 0.02});
    TruthSample truth;
    truth.t = t;
    truth.x = 0.05 * k, truth.vx = 0.05, truth.a_dist = -0.1, truth.immobilized = 0;
    truth.slip.fill(0.2);
    truth.sinkage.fill(0.004);
    log.truth.push_back(truth);
  }
  log.gps.push_back({0.5, 1.0, 2.0, 3.0, 0.1, 0.2, 0.0, 0.5, kMissing, 0.1});
  log.pose.push_back({0.5, 1.0, 2.0, 3.0, 0.0, 0.1, 0.2, 0.01, 0.01, kMissing});
  log.events.push_back({0.2, 0.4, "immobilized"});
  return log;
}

TEST(LogWriter, RoundTripIsExact) {
  const DriveLog original = MakeRockerLog();
  const std::string dir = testing::FreshDirectory("roundtrip");
  WriteDriveLog(original, dir);
  const DriveLog read = ReadDriveLog(dir);

  EXPECT_EQ(read.vehicle.name, "rover");
  EXPECT_EQ(read.vehicle.type, VehicleType::kRockerBogie6);
  EXPECT_EQ(read.vehicle.axle_spacing_m, 0.17);
  EXPECT_EQ(read.vehicle.tire.C2, -0.01);
  ASSERT_EQ(read.imu.size(), original.imu.size());
  for (size_t i = 0; i < read.imu.size(); ++i) {
    EXPECT_EQ(read.imu[i].t, original.imu[i].t);
    EXPECT_EQ(read.imu[i].az, original.imu[i].az);
    EXPECT_EQ(read.wheels[i].omega_radps, original.wheels[i].omega_radps);
    EXPECT_TRUE(Same(read.attitude[i].sd_pitch, original.attitude[i].sd_pitch));
    EXPECT_EQ(read.truth[i].slip[5], 0.2);
    EXPECT_EQ(read.truth[i].sinkage[0], 0.004);
    EXPECT_EQ(read.truth[i].a_dist, -0.1);
  }
  ASSERT_EQ(read.articulation.size(), 10u);
  EXPECT_EQ(read.articulation[1].side, Side::kRight);
  EXPECT_EQ(read.articulation[1].dz_front, 0.002);
  ASSERT_EQ(read.range.size(), 10u);
  EXPECT_EQ(read.range[1].d, 0.6);
  ASSERT_EQ(read.gps.size(), 1u);
  EXPECT_TRUE(Same(read.gps[0].sd_z, kMissing));
  EXPECT_EQ(read.pose[0].yaw, 0.2);
  ASSERT_EQ(read.events.size(), 1u);
  EXPECT_EQ(read.events[0].label, "immobilized");
  EXPECT_EQ(read.commands[4].v, 0.05);
  EXPECT_TRUE(read.warnings.empty());
}

TEST(LogWriter, AbsentStreamsAreNotWritten) {
  DriveLog log = MakeRockerLog();
  log.gps.clear();
  log.truth.clear();
  const std::string dir = testing::FreshDirectory("absent");
  WriteDriveLog(log, dir);
  const DriveLog read = ReadDriveLog(dir);
  EXPECT_FALSE(read.Has("gps.csv"));
  EXPECT_FALSE(read.Has("truth.csv"));
  EXPECT_TRUE(read.Has("pose.csv"));
}

}  // namespace
}  // namespace slipgraph
