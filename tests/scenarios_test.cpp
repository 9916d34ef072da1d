#include "sim/scenarios.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "io/log_reader.h"
#include "sim/simulation.h"
#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

namespace fs = std::filesystem;

std::string SimulateTo(const std::string& name, uint64_t seed, const std::string& tag) {
  const std::string dir = testing::FreshDirectory(tag);
  const sim::ScenarioRun run = sim::ExpandScenario(name, seed).at(0);
  sim::WriteSimulation(run.scenario, run.seed, sim::Simulate(run.scenario, run.seed), dir);
  return dir;
}

TEST(Scenarios, SameSeedGivesTheSameBytesAndAnotherSeedDoesNot) {
  const std::string a = SimulateTo("ward21/03", 1, "a");
  const std::string b = SimulateTo("ward21/03", 1, "b");
  const std::string c = SimulateTo("ward21/03", 2, "c");
  for (const char* file : {"imu.csv", "wheels.csv", "gps.csv", "truth.csv", "events.csv",
                           "vehicle.yaml", "sim.yaml"}) {
    EXPECT_EQ(testing::ReadFileBytes(fs::path(a) / file),
              testing::ReadFileBytes(fs::path(b) / file))
        << file;
  }
  EXPECT_NE(testing::ReadFileBytes(fs::path(a) / "imu.csv"),
            testing::ReadFileBytes(fs::path(c) / "imu.csv"));
}

TEST(Scenarios, Ward21HasTwentyHoldBacksOverAbout120Metres) {
  const std::vector<sim::ScenarioRun> runs = sim::ExpandScenario("ward21", 1);
  ASSERT_EQ(runs.size(), 21u);
  int holdbacks = 0, events = 0;
  double distance = 0.0;
  for (const sim::ScenarioRun& run : runs) {
    holdbacks += static_cast<int>(run.scenario.holdbacks.size());
    const sim::SimResult r = sim::Simulate(run.scenario, run.seed);
    events += static_cast<int>(r.log.events.size());
    for (size_t i = 1; i < r.log.truth.size(); ++i) {
      distance += std::hypot(r.log.truth[i].x - r.log.truth[i - 1].x,
                             r.log.truth[i].y - r.log.truth[i - 1].y);
    }
  }
  EXPECT_EQ(holdbacks, 20);
  EXPECT_EQ(events, 20);  // each hold-back immobilizes the robot, nothing else does
  EXPECT_NEAR(distance, 120.0, 15.0);
}

TEST(Scenarios, EveryScenarioWritesALogThatReadsBackCleanly) {
  std::vector<std::string> names = {"fig5",       "ward21/21",    "wilcox/0.5", "hidden/none",
                                    "ward21m/03", "hiddenm/none", "fig5m"};
  for (const sim::EffectInfo& effect : sim::EffectCatalogue()) {
    names.push_back("hidden/" + effect.name);
  }
  for (const std::string& name : names) {
    std::string tag = name;
    for (char& ch : tag) ch = ch == '/' ? '_' : ch;
    const std::string dir = SimulateTo(name, 5, tag);
    const DriveLog log = ReadDriveLog(dir);
    EXPECT_TRUE(log.warnings.empty()) << name;
    EXPECT_FALSE(log.imu.empty()) << name;
    EXPECT_EQ(log.truth.size(), log.wheels.size()) << name;
    EXPECT_TRUE(fs::exists(fs::path(dir) / "sim.yaml")) << name;
  }
}

TEST(Scenarios, HiddenSuiteHasOneLogPerEffectAndNone) {
  const std::vector<sim::ScenarioRun> runs = sim::ExpandScenario("hidden", 1);
  EXPECT_EQ(runs.size(), sim::EffectCatalogue().size() + 1);
  EXPECT_EQ(runs[0].relative_directory, "none");
  EXPECT_TRUE(runs[0].scenario.effects.empty());
  for (size_t i = 1; i < runs.size(); ++i) EXPECT_EQ(runs[i].scenario.effects.size(), 1u);
}

TEST(Scenarios, WilcoxSuitesCoverTheRoughnessSweepAndTheLeftRightCheck) {
  const std::vector<sim::ScenarioRun> runs = sim::ExpandScenario("wilcox", 1);
  ASSERT_EQ(runs.size(), 40u);  // 5 roughness levels x 8 runs
  EXPECT_EQ(runs.front().relative_directory, "r0.25cm_run01");
  EXPECT_DOUBLE_EQ(runs.back().scenario.rocker.roughness_rms_m, 0.04);
  for (const sim::ScenarioRun& run : runs) {
    EXPECT_DOUBLE_EQ(run.scenario.rocker.slip_mean, 0.2);
    EXPECT_EQ(run.scenario.vehicle.type, VehicleType::kRockerBogie6);
  }
  const std::vector<sim::ScenarioRun> lr = sim::ExpandScenario("wilcox_lr", 1);
  int asymmetric = 0;
  for (const sim::ScenarioRun& run : lr) asymmetric += run.scenario.rocker.left_extra_sinkage_m > 0;
  EXPECT_EQ(asymmetric, 4);
  EXPECT_EQ(lr.size(), 8u);
}

TEST(Scenarios, Ipd35IsThirtyFiveMinutesOfTrackedDrivingOverFourTerrains) {
  const sim::Scenario sc = sim::ExpandScenario("ipd35", 1).at(0).scenario;
  EXPECT_EQ(sc.vehicle.type, VehicleType::kSkidSteer);
  EXPECT_NEAR(sc.duration_s(), 35.0 * 60.0, 10.0);
  std::set<std::string> terrains;
  for (const sim::TerrainPatch& patch : sc.course.patches) terrains.insert(patch.terrain.name);
  EXPECT_EQ(terrains, (std::set<std::string>{"asphalt", "grass", "loose_rock", "soft_dirt"}));
  double max_v = 0.0, max_w = 0.0;
  for (const sim::CommandSegment& c : sc.commands) {
    max_v = std::max(max_v, c.v_mps), max_w = std::max(max_w, std::abs(c.yaw_rate_radps));
  }
  EXPECT_LE(max_v, 1.7);
  EXPECT_GT(max_v, 1.5);
  EXPECT_LE(max_w, 3.0);
  EXPECT_GT(max_w, 2.0);
}

TEST(Scenarios, AnEffectAVehicleSimulatorCannotApplyIsAnError) {
  sim::Scenario sc = sim::ExpandScenario("wilcox/1", 1).at(0).scenario;
  sc.effects["quadratic_drag"] = 40.0;
  EXPECT_THROW(sim::Simulate(sc, 1), std::invalid_argument);
  EXPECT_TRUE(sim::EffectSupported(VehicleType::kSkidSteer, "gps_velocity_averaging"));
  EXPECT_FALSE(sim::EffectSupported(VehicleType::kRockerBogie6, "gps_velocity_averaging"));
  EXPECT_TRUE(sim::EffectSupported(VehicleType::kDiffDriveCastor, "corrugation"));
}

TEST(Scenarios, UnknownScenarioIsNamed) {
  try {
    sim::ExpandScenario("moon_landing", 1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("moon_landing"), std::string::npos);
  }
  EXPECT_THROW(sim::ExpandScenario("ward21/22", 1), std::invalid_argument);
}

}  // namespace
}  // namespace slipgraph
