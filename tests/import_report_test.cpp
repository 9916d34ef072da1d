// The importers' last step: the log they return reads back as the format requires.
#include "io/import_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/log_reader.h"
#include "io/log_writer.h"
#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

TEST(KeepReadableSamples, SortsDropsWhatTheFormatRefusesAndSaysHowMany) {
  DriveLog log;
  log.vehicle = ReadDriveLog(testing::WriteValidLog("import_vehicle")).vehicle;
  for (double t : {0.02, 0.00, 0.01, 0.01, 0.03}) log.imu.push_back({t, 0.1, 0, 9.8, 0, 0, 0});
  log.imu[4].gz = kMissing;  // a corrupted float
  WheelSample w;
  w.omega_radps.fill(kMissing);  // the third and later slots are not this vehicle's wheels
  w.t = 0.0, w.omega_radps[0] = 1.0, w.omega_radps[1] = 1.0;
  log.wheels.push_back(w);
  w.t = 0.1, w.omega_radps[1] = INFINITY;
  log.wheels.push_back(w);
  GpsSample g{};
  g.t = 0.5, g.vx = kMissing;  // a velocity by central difference over a repeated fix stamp
  log.gps.push_back(g);
  log.present_files = {"imu.csv", "wheels.csv", "gps.csv"};

  ImportReport report;
  KeepReadableSamples(&log, &report);
  ASSERT_EQ(log.imu.size(), 3u);
  EXPECT_EQ(log.imu[0].t, 0.00);
  EXPECT_EQ(log.imu[1].t, 0.01);
  EXPECT_EQ(log.imu[2].t, 0.02);
  EXPECT_EQ(log.wheels.size(), 1u);
  EXPECT_TRUE(log.gps.empty());
  ASSERT_EQ(report.lines.size(), 3u);
  EXPECT_EQ(report.lines[0],
            "imu: 2 of 5 samples dropped (a value not finite, or a stamp repeated)");
  EXPECT_EQ(report.lines[1].rfind("wheels: 1 of 2", 0), 0u) << report.lines[1];
  EXPECT_EQ(report.lines[2].rfind("gps: 1 of 1", 0), 0u) << report.lines[2];

  const std::string dir = testing::FreshDirectory("kept_samples");
  WriteDriveLog(log, dir);
  EXPECT_EQ(ReadDriveLog(dir).imu.size(), 3u);  // reads back
}

TEST(KeepReadableSamples, ALogThatReadsAlreadyIsUnchangedAndUnreported) {
  DriveLog log;
  log.vehicle.type = VehicleType::kDiffDriveCastor;
  for (double t : {0.0, 0.01, 0.02}) log.imu.push_back({t, 0.1, 0, 9.8, 0, 0, 0});
  ImportReport report;
  KeepReadableSamples(&log, &report);
  EXPECT_EQ(log.imu.size(), 3u);
  EXPECT_TRUE(report.lines.empty());
}

}  // namespace
}  // namespace slipgraph
