#include "io/log_tables.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace slipgraph {
namespace {

DriveLog TwoSampleLog() {
  DriveLog log;
  log.vehicle.type = VehicleType::kRockerBogie6;
  for (int k = 0; k < 2; ++k) {
    log.imu.push_back({0.01 * k, 0.1, 0.0, 9.81, 0.0, 0.0, 0.2});
    WheelSample w;
    w.t = 0.01 * k;
    for (int i = 0; i < 6; ++i) w.omega_radps[i] = i + k;
    log.wheels.push_back(w);
  }
  log.events.push_back({0.0, 0.01, "hold-back"});
  return log;
}

TEST(LogTables, ListsTheRequiredFilesAndOnlyTheStreamsTheLogHas) {
  DriveLog log = TwoSampleLog();
  EXPECT_EQ(LogTableFiles(log), (std::vector<std::string>{"imu.csv", "wheels.csv", "events.csv"}));
  log.present_files.push_back("gps.csv");  // read, with no fix: still a file of the log
  EXPECT_EQ(LogTableFiles(log),
            (std::vector<std::string>{"imu.csv", "wheels.csv", "gps.csv", "events.csv"}));
}

TEST(LogTables, NamesTheWheelsColumnsByTheVehicleAndKeepsTextColumnsAsText) {
  const DriveLog log = TwoSampleLog();
  const LogTable wheels = StreamTable(log, "wheels.csv");
  ASSERT_EQ(wheels.columns.size(), 7u);
  EXPECT_EQ(wheels.columns[0].name, "t");
  EXPECT_EQ(wheels.columns[1].name, WheelNames(VehicleType::kRockerBogie6)[0]);
  EXPECT_EQ(wheels.rows(), 2u);
  EXPECT_EQ(wheels.columns[6].numbers[1], 6.0);
  const LogTable events = StreamTable(log, "events.csv");
  ASSERT_EQ(events.columns.size(), 3u);
  EXPECT_TRUE(events.columns[2].is_text);
  EXPECT_EQ(events.columns[2].texts, std::vector<std::string>{"hold-back"});
  EXPECT_EQ(events.rows(), 1u);
}

TEST(LogTables, ATableOfAnAbsentStreamHasItsColumnsAndNoRows) {
  const LogTable gps = StreamTable(TwoSampleLog(), "gps.csv");
  EXPECT_EQ(gps.columns.size(), 10u);
  EXPECT_EQ(gps.rows(), 0u);
}

TEST(LogTables, AFileThatIsNotAStreamIsAnErrorNamingTheStreams) {
  try {
    StreamTable(TwoSampleLog(), "vehicle.yaml");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'vehicle.yaml'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("truth.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace slipgraph
