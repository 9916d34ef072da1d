#include "io/log_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "io/input_error.h"
#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

using testing::WriteValidLog;

// Reads `dir` expecting an InputError; returns it for field checks.
InputError ReadExpectingError(const std::string& dir) {
  try {
    ReadDriveLog(dir);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError reading " << dir;
  return InputError("", 0, "", "", "");
}

std::string FileName(const InputError& error) {
  return std::filesystem::path(error.file()).filename().string();
}

TEST(LogReader, ReadsValidLogWithCommentsAnyColumnOrderExtraColumnsAndMissingOptionals) {
  const DriveLog log = ReadDriveLog(WriteValidLog("valid"));
  EXPECT_EQ(log.vehicle.name, "lagr");
  EXPECT_EQ(log.vehicle.type, VehicleType::kDiffDriveCastor);
  EXPECT_DOUBLE_EQ(log.vehicle.tire.At, 20.0);
  ASSERT_EQ(log.imu.size(), 4u);
  EXPECT_DOUBLE_EQ(log.imu[2].ay, 0.01);
  ASSERT_EQ(log.wheels.size(), 3u);
  EXPECT_DOUBLE_EQ(log.wheels[2].omega_radps[0], 4.0);  // left, though it is the third column
  EXPECT_DOUBLE_EQ(log.wheels[2].omega_radps[1], 4.1);
  ASSERT_EQ(log.gps.size(), 3u);
  EXPECT_DOUBLE_EQ(log.gps[0].sd_xy, 0.4);
  EXPECT_TRUE(std::isnan(log.gps[1].sd_xy));  // empty cell
  EXPECT_TRUE(std::isnan(log.gps[2].sd_xy));  // "nan"
  EXPECT_TRUE(std::isnan(log.gps[0].sd_v));   // column absent
  EXPECT_TRUE(log.Has("gps.csv"));
  EXPECT_FALSE(log.Has("attitude.csv"));
  EXPECT_TRUE(log.attitude.empty());
  EXPECT_TRUE(log.warnings.empty());
}

TEST(LogReader, ReadsFilesHeldInMemoryAsFromTheirDirectory) {
  const DriveLog from_disk = ReadDriveLog(WriteValidLog("in_memory_twin"));
  const DriveLog in_memory =
      ReadDriveLog(LogFilesInMemory("memory/valid", testing::ValidLogFiles()));
  EXPECT_EQ(in_memory.directory, "memory/valid");
  ASSERT_EQ(in_memory.imu.size(), from_disk.imu.size());
  EXPECT_EQ(in_memory.imu.back().az, from_disk.imu.back().az);
  EXPECT_EQ(in_memory.wheels.size(), from_disk.wheels.size());
  EXPECT_EQ(in_memory.gps.size(), from_disk.gps.size());
  EXPECT_EQ(in_memory.present_files, from_disk.present_files);

  try {
    ReadDriveLog(LogFilesInMemory("memory/bad", testing::ValidLogFiles({{"imu.csv", "t\nx\n"}})));
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "memory/bad/imu.csv");
  }
}

// A recorder stopped inside the IMU's last number: an error naming the row, which --skip-bad
// drops with a warning, keeping every whole row.
TEST(LogReader, ACutLastRowIsAnErrorThatSkipBadDrops) {
  const std::string imu =
      "t,ax,ay,az,gx,gy,gz\n"
      "0.00,0.10,0.00,9.81,0.00,0.00,0.01\n"
      "0.01,0.11,0.00,9.80,0.00,0.00,0.01\n"
      "0.02,0.12,0.01,9.81,0.00,0.00,0.02\n"
      "0.03,0.10,0.00,9.82,0.00,0.00,0.0";
  const LogFiles files = LogFilesInMemory("cut", testing::ValidLogFiles({{"imu.csv", imu}}));
  try {
    ReadDriveLog(files);
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 5);
    EXPECT_EQ(e.column(), "gz");
  }
  ReadOptions options;
  options.skip_bad = true;
  const DriveLog log = ReadDriveLog(files, options);
  EXPECT_EQ(log.imu.size(), 3u);
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_NE(log.warnings[0].find("cut short"), std::string::npos) << log.warnings[0];
}

TEST(LogReader, MissingRequiredFileNamesIt) {
  const InputError e = ReadExpectingError(WriteValidLog("no_imu", {{"imu.csv", ""}}));
  EXPECT_EQ(FileName(e), "imu.csv");
  EXPECT_NE(std::string(e.what()).find("required file is missing"), std::string::npos);
}

TEST(LogReader, MissingRequiredColumnNamesFileLineAndColumn) {
  const InputError e = ReadExpectingError(
      WriteValidLog("no_right", {{"wheels.csv", "# comment\nt,left\n0.0,4.0\n"}}));
  EXPECT_EQ(FileName(e), "wheels.csv");
  EXPECT_EQ(e.line(), 2);  // the header line, after the comment
  EXPECT_EQ(e.column(), "right");
}

TEST(LogReader, NonNumericCellNamesFileLineColumnAndValue) {
  const InputError e = ReadExpectingError(WriteValidLog(
      "abc", {{"imu.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,9.8,0,0,0\n0.01,abc,0,9.8,0,0,0\n"}}));
  EXPECT_EQ(FileName(e), "imu.csv");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), "ax");
  EXPECT_EQ(e.value(), "abc");
}

TEST(LogReader, NanInRequiredColumnIsRejected) {
  const InputError e = ReadExpectingError(WriteValidLog(
      "nan", {{"imu.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,9.8,0,0,0\n0.01,0,0,9.8,0,0,nan\n"}}));
  EXPECT_EQ(FileName(e), "imu.csv");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), "gz");
  EXPECT_EQ(e.value(), "nan");
}

TEST(LogReader, InfIsRejectedEvenInOptionalColumn) {
  const InputError e = ReadExpectingError(WriteValidLog(
      "inf", {{"gps.csv", "t,x,y,z,vx,vy,vz,sd_xy\n0,0,0,0,1,0,0,0.5\n1,1,0,0,1,0,0,inf\n"}}));
  EXPECT_EQ(FileName(e), "gps.csv");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), "sd_xy");
  EXPECT_EQ(e.value(), "inf");
}

TEST(LogReader, RepeatedTimeStampIsRejected) {
  const InputError e = ReadExpectingError(
      WriteValidLog("repeat", {{"wheels.csv", "t,left,right\n0.0,1,1\n0.01,1,1\n0.01,1,1\n"}}));
  EXPECT_EQ(FileName(e), "wheels.csv");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.column(), "t");
  EXPECT_EQ(e.value(), "0.01");
  EXPECT_NE(std::string(e.what()).find("repeated"), std::string::npos);
}

TEST(LogReader, DecreasingTimeStampIsRejected) {
  const InputError e = ReadExpectingError(
      WriteValidLog("decrease", {{"wheels.csv", "t,left,right\n0.0,1,1\n0.02,1,1\n0.01,1,1\n"}}));
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.column(), "t");
  EXPECT_NE(std::string(e.what()).find("decreasing"), std::string::npos);
}

TEST(LogReader, UnknownVehicleTypeNamesKeyLineAndValue) {
  std::string yaml = testing::kLagrVehicleYaml;
  yaml.replace(yaml.find("diff_drive_castor"), 17, "hovercraft");
  const InputError e = ReadExpectingError(WriteValidLog("hover", {{"vehicle.yaml", yaml}}));
  EXPECT_EQ(FileName(e), "vehicle.yaml");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), "type");
  EXPECT_EQ(e.value(), "hovercraft");
}

TEST(LogReader, MissingYamlKeyNeededByTheTypeIsNamed) {
  // diff_drive_castor needs cg_to_front (eqs. 3-5); skid_steer does not.
  std::string yaml = testing::kLagrVehicleYaml;
  yaml.erase(yaml.find("cg_to_front: 0.35\n"), 18);
  const InputError e = ReadExpectingError(WriteValidLog("no_a", {{"vehicle.yaml", yaml}}));
  EXPECT_EQ(FileName(e), "vehicle.yaml");
  EXPECT_EQ(e.column(), "cg_to_front");
  EXPECT_NE(std::string(e.what()).find("missing key"), std::string::npos);

  std::string rocker = testing::kLagrVehicleYaml;
  rocker.replace(rocker.find("diff_drive_castor"), 17, "rocker_bogie6");
  const InputError r = ReadExpectingError(WriteValidLog("rocker", {{"vehicle.yaml", rocker}}));
  EXPECT_EQ(r.column(), "axle_spacing");
}

TEST(LogReader, NonNumericYamlValueNamesLineAndKey) {
  std::string yaml = testing::kLagrVehicleYaml;
  yaml.replace(yaml.find("117.0"), 5, "heavy");
  const InputError e = ReadExpectingError(WriteValidLog("heavy", {{"vehicle.yaml", yaml}}));
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), "mass");
  EXPECT_EQ(e.value(), "heavy");
}

TEST(LogReader, SkipBadDropsOnlyTheBadRowsAndSaysSo) {
  const std::string dir = WriteValidLog(
      "skip", {{"gps.csv", "t,x,y,z,vx,vy,vz\n0,0,0,0,1,0,0\n1,1,0,0,oops,0,0\n2,2,0,0,1,0,0\n"}});
  EXPECT_THROW(ReadDriveLog(dir), InputError);
  ReadOptions options;
  options.skip_bad = true;
  const DriveLog log = ReadDriveLog(dir, options);
  ASSERT_EQ(log.gps.size(), 2u);  // the good rows are kept
  EXPECT_DOUBLE_EQ(log.gps[1].t, 2.0);
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_NE(log.warnings[0].find("gps.csv:3"), std::string::npos);
  EXPECT_NE(log.warnings[0].find("'vx'"), std::string::npos);
  EXPECT_EQ(log.imu.size(), 4u);
}

// One forward time typo (t = 1000) made every later row "decreasing": --skip-bad dropped them
// all. More bad rows than --skip-bad drops is an error quoting the first, which names the typo.
TEST(LogReader, SkipBadHasALimit) {
  std::string gps = "t,x,y,z,vx,vy,vz\n";
  for (int i = 0; i < 40; ++i) {
    gps += std::to_string(i == 5 ? 1000 : i) + ",0,0,0,1,0,0\n";
  }
  const std::string dir = WriteValidLog("skip_limit", {{"gps.csv", gps}});
  ReadOptions options;
  options.skip_bad = true;
  try {
    ReadDriveLog(dir, options);
    ADD_FAILURE() << "34 of 40 rows dropped without an error";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("34 of 40 rows are bad"), std::string::npos) << what;
    EXPECT_NE(what.find("gps.csv:8"), std::string::npos) << what;  // the first row after it
    EXPECT_NE(what.find("previous 1000"), std::string::npos) << what;
  }
  options.max_bad_fraction = 1.0;  // the user's choice: drop them
  EXPECT_EQ(ReadDriveLog(dir, options).gps.size(), 6u);
}

// A row's sd of zero was replaced silently by vehicle.yaml's.
TEST(LogReader, ARowSdOfZeroIsAnErrorNamingTheColumn) {
  const std::string dir = WriteValidLog(
      "sd_zero", {{"gps.csv", "t,x,y,z,vx,vy,vz,sd_v\n0,0,0,0,1,0,0,0.1\n1,1,0,0,1,0,0,0\n"}});
  const InputError error = ReadExpectingError(dir);
  EXPECT_EQ(FileName(error), "gps.csv");
  EXPECT_EQ(error.line(), 3);
  EXPECT_EQ(error.column(), "sd_v");
}

TEST(LogReader, SkipBadLeavesOutAnOptionalFileWithoutItsHeader) {
  const std::string dir = WriteValidLog("nogpsheader", {{"gps.csv", "t,x,y\n0,0,0\n"}});
  EXPECT_THROW(ReadDriveLog(dir), InputError);
  ReadOptions options;
  options.skip_bad = true;
  const DriveLog log = ReadDriveLog(dir, options);
  EXPECT_FALSE(log.Has("gps.csv"));
  EXPECT_TRUE(log.gps.empty());
  ASSERT_EQ(log.warnings.size(), 1u);
  EXPECT_NE(log.warnings[0].find("optional file left out"), std::string::npos);
}

TEST(LogReader, SkipBadNeverSkipsARequiredFile) {
  ReadOptions options;
  options.skip_bad = true;
  EXPECT_THROW(ReadDriveLog(WriteValidLog("nowheels", {{"wheels.csv", ""}}), options), InputError);
}

TEST(LogReader, ArticulationTimeIsIncreasingPerSideAndRangeMayRepeat) {
  std::string rocker = testing::kLagrVehicleYaml;
  rocker.replace(rocker.find("diff_drive_castor"), 17, "rocker_bogie6");
  rocker += "axle_spacing: 0.35\n";
  const std::string dir = WriteValidLog(
      "rocker_ok",
      {{"vehicle.yaml", rocker},
       {"wheels.csv", "t,fl,ml,rl,fr,mr,rr\n0,1,1,1,1,1,1\n0.1,1,1,1,1,1,1\n"},
       {"articulation.csv",
        "t,side,dz_mid,dz_front\n0,left,0.01,0.02\n0,right,0,0\n"
        "0.1,left,0.01,0.02\n0.1,right,0,0\n"},
       {"range.csv", "t,side,d,dz\n0,left,1.0,0.01\n0,left,1.1,0.02\n0,right,1.0,0.0\n"}});
  const DriveLog log = ReadDriveLog(dir);
  EXPECT_EQ(log.articulation.size(), 4u);
  EXPECT_EQ(log.articulation[1].side, Side::kRight);
  EXPECT_EQ(log.range.size(), 3u);
  EXPECT_EQ(log.wheel_count(), 6);

  const std::string bad_side = WriteValidLog(
      "rocker_bad", {{"vehicle.yaml", rocker},
                     {"wheels.csv", "t,fl,ml,rl,fr,mr,rr\n0,1,1,1,1,1,1\n"},
                     {"articulation.csv", "t,side,dz_mid,dz_front\n0,middle,0.01,0.02\n"}});
  const InputError e = ReadExpectingError(bad_side);
  EXPECT_EQ(e.column(), "side");
  EXPECT_EQ(e.value(), "middle");
}

TEST(LogReader, NotADirectoryIsAnError) {
  EXPECT_THROW(ReadDriveLog("/nonexistent/log"), InputError);
}

}  // namespace
}  // namespace slipgraph
