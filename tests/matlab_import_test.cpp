// Import of the WVU Pathfinder MATLAB v7.3 log (../shared/data/real) with the shipped mapping:
// row counts, plausibility, deliberately wrong mappings named by the checks, and the EKF running
// through it without a NaN; the smoother and diagnose too, diagnose naming the streams the model
// fails on (docs/real_logs.md). Skipped when the shared real data is not beside the repository.
#include "io/matlab_import.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/plausibility.h"
#include "io/yaml_config.h"
#include "solvers/ekf_runner.h"
#include "tests/import_test_util.h"
#include "workbench/diagnosis.h"

namespace slipgraph {
namespace {

const std::string kSource =
    std::string(SLIPGRAPH_SOURCE_DIR) + "/../shared/data/real/wvu_pathfinder/s5t1.mat";
const std::string kMapping =
    std::string(SLIPGRAPH_SOURCE_DIR) + "/data/mappings/wvu_pathfinder.yaml";
const std::string kVehicle =
    std::string(SLIPGRAPH_SOURCE_DIR) + "/data/mappings/wvu_pathfinder_vehicle.yaml";

DriveLog Import(const std::string& mapping) {
  std::vector<std::string> warnings;
  ImportReport report;
  return ImportMatlab(kSource, mapping, ReadVehicleYaml(kVehicle, &warnings), &report);
}

// The shipped mapping with one line replaced.
std::string Altered(const std::string& from, const std::string& to) {
  return testing::AlteredMapping(kMapping, from, to, "altered_mapping.yaml");
}

using testing::Mentions;

class MatlabImport : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kSource)) GTEST_SKIP() << kSource << " not present";
  }
};

TEST_F(MatlabImport, ShippedMappingImportsAndPassesThePlausibilityChecks) {
  const DriveLog log = Import(kMapping);
  EXPECT_EQ(log.imu.size(), 44249u);
  EXPECT_EQ(log.wheels.size(), 1770u);
  EXPECT_EQ(log.gps.size(), 1770u);
  EXPECT_NEAR(std::min(log.imu.front().t, log.wheels.front().t), 0.0, 1e-9);
  const Plausibility p = CheckPlausibility(log);
  EXPECT_TRUE(p.problems.empty()) << p.problems.front();
  EXPECT_NEAR(p.figures.rest_az_mps2, 9.8, 0.3);
  EXPECT_GT(p.figures.wheel_gyro_yaw_correlation, 0.5);
}

// test17run.mat has no GNSS stamps: the s5t1 mapping names the missing variable, its own mapping
// takes the fixes at the odometry's stamps (docs/real_logs.md).
TEST_F(MatlabImport, TheSecondLogImportsWithItsOwnMapping) {
  const std::string source =
      std::string(SLIPGRAPH_SOURCE_DIR) + "/../shared/data/real/wvu_pathfinder/test17run.mat";
  if (!std::filesystem::exists(source)) GTEST_SKIP() << source << " not present";
  std::vector<std::string> warnings;
  const Vehicle vehicle = ReadVehicleYaml(kVehicle, &warnings);
  ImportReport report;
  try {
    ImportMatlab(source, kMapping, vehicle, &report);
    ADD_FAILURE() << "the s5t1 mapping imported test17run.mat";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("tTGPS"), std::string::npos) << e.what();
  }
  const DriveLog log = ImportMatlab(
      source, std::string(SLIPGRAPH_SOURCE_DIR) + "/data/mappings/wvu_pathfinder_test17.yaml",
      vehicle, &report);
  EXPECT_EQ(log.imu.size(), 17611u);
  EXPECT_EQ(log.wheels.size(), 705u);
  ASSERT_EQ(log.gps.size(), 705u);
  EXPECT_EQ(log.gps[100].t, log.wheels[100].t);
  const Plausibility p = CheckPlausibility(log);
  EXPECT_TRUE(p.problems.empty()) << p.problems.front();
  EXPECT_NEAR(p.figures.rest_az_mps2, 9.8, 0.3);
}

TEST_F(MatlabImport, WrongMappingsAreNamed) {
  EXPECT_TRUE(Mentions(CheckPlausibility(Import(Altered("frame: z_down", "frame: z_up"))),
                       "z axis points down"));
  EXPECT_TRUE(Mentions(CheckPlausibility(Import(Altered("left_sign: -1", "left_sign: 1"))),
                       "one side reads backwards"));
  const std::string swapped = Altered(
      "left: [frontLeftVel, rearLeftVel]\n  right: [frontRightVel, rearRightVel]\n  "
      "left_sign: -1\n  right_sign: 1",
      "left: [frontRightVel, rearRightVel]\n  right: [frontLeftVel, rearLeftVel]\n  "
      "left_sign: 1\n  right_sign: -1");
  EXPECT_TRUE(Mentions(CheckPlausibility(Import(swapped)), "left and right wheels swapped"));
}

TEST_F(MatlabImport, TheEkfRunsThroughWithoutANaN) {
  const DriveLog log = Import(kMapping);
  const FilterResult result = RunEkf(log, DefaultModelConfig(log.vehicle));
  ASSERT_EQ(result.estimates.size(), log.wheels.size());
  for (const WardEstimate& e : result.estimates) {
    for (double v : e.x) ASSERT_TRUE(std::isfinite(v)) << "t=" << e.t;
    for (double sd : e.sd) ASSERT_TRUE(std::isfinite(sd)) << "t=" << e.t;
  }
}

}  // namespace
}  // namespace slipgraph

namespace slipgraph {
namespace {

TEST_F(MatlabImport, SmootherAndDiagnoseRunThroughAndSayWhereTheModelFails) {
  DriveLog log = Import(kMapping);
  log.directory = "pathfinder";
  DiagnosisOptions options;
  options.smoother.max_iterations = 60;
  const Diagnosis d = Diagnose(log, DefaultModelConfig(log.vehicle), options);
  ASSERT_EQ(d.solution.estimates.size(), log.wheels.size());
  for (const WardEstimate& e : d.solution.estimates) {
    for (double v : e.x) ASSERT_TRUE(std::isfinite(v)) << "t=" << e.t;
    for (double sd : e.sd) ASSERT_TRUE(std::isfinite(sd)) << "t=" << e.t;
  }
  // Bounds stated in docs/real_logs.md: the encoders within their stated noise; the GNSS
  // velocity (central differences of 10 Hz fixes) and the gyro far outside theirs, and said.
  for (const char* name : {"encoder_left", "encoder_right"}) {
    EXPECT_LT(testing::Named(d.streams, name).rms, 1.0) << name;
  }
  for (const char* name : {"gnss", "gyro"}) {
    const StreamReport& s = testing::Named(d.streams, name);
    EXPECT_GT(s.rms, 3.0) << name;
    EXPECT_FALSE(s.consistent) << name;
  }
  // The EKF's GNSS innovations: NIS mean about 190, 39 % inside the 95 % bound.
  EXPECT_GT(testing::Named(d.filter, "gnss").nis_mean, 20.0);
  // The candidates that fit are not physical (a negative drag, a wheel radius off by 100 %):
  // implausible, none offered, and the failures left unexplained.
  EXPECT_EQ(BestExplanation(d.candidates), nullptr);
  EXPECT_FALSE(d.explained);
}

TEST_F(MatlabImport, DivergenceIsCaughtAndReportedNotANaN) {
  // With the data's effective skid-steer track (1.78 m) as the force model's lever arm, the yaw
  // dynamics blow up (it went NaN after 3.4 s before the guard): now every estimate is finite
  // and the resets are counted.
  DriveLog log = Import(kMapping);
  log.vehicle.track_width_m = 1.78;
  const FilterResult result = RunEkf(log, DefaultModelConfig(log.vehicle));
  ASSERT_EQ(result.estimates.size(), log.wheels.size());
  for (const WardEstimate& e : result.estimates) {
    for (double v : e.x) ASSERT_TRUE(std::isfinite(v)) << "t=" << e.t;
  }
  EXPECT_GT(result.stats.divergence_resets, 0);
  EXPECT_NE(DescribeFilterRun(result).find("DIVERGED"), std::string::npos);
}

}  // namespace
}  // namespace slipgraph

#include "io/input_error.h"

namespace slipgraph {
namespace {

TEST(MatlabImportMapping, AnUnknownKeyIsAnErrorNamingIt) {
  const std::string path = ::testing::TempDir() + "/typo_mapping.yaml";
  std::ofstream(path) << "format: matlab_v73\nwheels: {t: tTodom, left: a, right: b, "
                         "lefts_sign: -1}\n";
  std::vector<std::string> warnings;
  ImportReport report;
  try {
    ImportMatlab("/nonexistent.mat", path, Vehicle(), &report);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wheels.lefts_sign"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace slipgraph
