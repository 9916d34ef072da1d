// The bundled logs in data/ are exactly what the simulator makes today (see data/README.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/log_reader.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

namespace fs = std::filesystem;

void ExpectBundledMatchesSimulation(const std::string& folder, const std::string& scenario) {
  const fs::path bundled = fs::path(SLIPGRAPH_DATA_DIR) / folder;
  ASSERT_TRUE(fs::exists(bundled / "vehicle.yaml")) << bundled;
  const std::string fresh = testing::FreshDirectory(folder);
  const sim::ScenarioRun run = sim::ExpandScenario(scenario, 1).at(0);
  sim::WriteSimulation(run.scenario, run.seed, sim::Simulate(run.scenario, run.seed), fresh);
  for (const auto& entry : fs::directory_iterator(fresh)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(testing::ReadFileBytes(entry.path()), testing::ReadFileBytes(bundled / name))
        << folder << "/" << name << " differs from a fresh simulation: regenerate it with the "
        << "command in data/README.md";
  }
  EXPECT_TRUE(ReadDriveLog(bundled.string()).warnings.empty());
}

TEST(BundledData, SampleIsWard21Run01) { ExpectBundledMatchesSimulation("sample", "ward21/01"); }

TEST(BundledData, HiddenQuadraticDragLog) {
  ExpectBundledMatchesSimulation("hidden_quadratic_drag", "hidden/quadratic_drag");
}

TEST(BundledData, HiddenClockOffsetLog) {
  ExpectBundledMatchesSimulation("hidden_clock_offset", "hidden/clock_offset");
}

}  // namespace
}  // namespace slipgraph
