// Wilcox's baseline on a hand-made profile (noise-free, point contact): it recovers the advance
// per cycle and the sinkage; the left/right check catches a side that sinks more; and a small
// Monte Carlo on simulated wilcox runs (the full figures: docs/wilcox.md).
#include "solvers/wilcox_baseline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>

#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "tests/wilcox_test_logs.h"

namespace slipgraph {
namespace {

using testing::HandMadeLog;
using testing::PointContact;

TEST(WilcoxBaseline, RecoversAdvanceAndSinkageOnAHandMadeProfile) {
  const DriveLog log = HandMadeLog(0.003, 0.003);
  const WilcoxResult result = EstimateWilcoxBaseline(log, PointContact());
  ASSERT_EQ(result.sides.size(), 2u);
  for (const WilcoxSide& side : result.sides) {
    ASSERT_EQ(side.cycles.size(), 40u);
    EXPECT_NEAR(side.total_rim_m, 2.5, 1e-9);
    // Per cycle within 8 mm (the histograms' 1 cm bins and linear interpolation between ranged
    // points 2 cm apart limit a single match even without noise); the errors do not build up.
    for (const WilcoxCycle& c : side.cycles) EXPECT_NEAR(c.advance_m, 0.05, 0.008) << c.t;
    EXPECT_NEAR(side.total_advance_m, 2.0, 0.02);  // 1 % of the distance
    EXPECT_NEAR(side.cycles.back().sinkage_front_m, 0.003, 0.003);
  }
  EXPECT_TRUE(result.sides_agree) << result.agreement;
  const WilcoxScore score = ScoreWilcox(log, result);
  EXPECT_LT(score.odometry_error_fraction, 0.01);
  EXPECT_NEAR(score.rim_odometry_error_fraction, 0.25, 1e-6);
}

TEST(WilcoxBaseline, LeftRightCheckFlagsASideThatSinksMore) {
  const DriveLog log = HandMadeLog(0.013, 0.003);
  const WilcoxResult result = EstimateWilcoxBaseline(log, PointContact());
  EXPECT_FALSE(result.sides_agree) << result.agreement;
}

TEST(WilcoxBaseline, RejectsALogWithoutArticulation) {
  DriveLog log = HandMadeLog(0.003, 0.003);
  log.articulation.clear();
  EXPECT_THROW(EstimateWilcoxBaseline(log), std::invalid_argument);
}

TEST(WilcoxBaseline, SmallMonteCarloOnSimulatedRoughTerrain) {
  // Four simulated 2 cm runs, 10 % prior: measured 1.13 % mean over eight (docs/wilcox.md), the
  // rim motion alone 25 %.
  std::vector<double> errors;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox", 1)) {
    if (run.relative_directory.rfind("r2cm", 0) != 0) continue;
    if (errors.size() >= 4) break;
    const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
    errors.push_back(ScoreWilcox(log, EstimateWilcoxBaseline(log)).odometry_error_fraction);
  }
  ASSERT_EQ(errors.size(), 4u);
  for (double e : errors) EXPECT_LT(e, 0.02);
}

}  // namespace
}  // namespace slipgraph

namespace slipgraph {
namespace {

TEST(WilcoxBaseline, LeftRightCheckOnSimulatedRuns) {
  // wilcox_lr: the asymmetric runs sink 1 cm more on the left in soft patches.
  int flagged_asym = 0, flagged_sym = 0;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox_lr", 1)) {
    if (run.relative_directory != "asym_run01" && run.relative_directory != "sym_run01") continue;
    const WilcoxResult result = EstimateWilcoxBaseline(sim::Simulate(run.scenario, run.seed).log);
    (run.relative_directory == "asym_run01" ? flagged_asym : flagged_sym) += !result.sides_agree;
  }
  EXPECT_EQ(flagged_asym, 1);
  EXPECT_EQ(flagged_sym, 0);
}

}  // namespace
}  // namespace slipgraph

namespace slipgraph {
namespace {

// Slip that grows with slope (sim: 20 % + the slope, a hill up and down, wilcox_slope) and a user
// who knows the slip: the slope-dependent prior keeps the distance travelled closer along the way
// than the constant one (measured on r1cm_run01: 248 -> 57 mm with the 1 % prior).
TEST(WilcoxBaseline, SlopeDependentPriorFollowsTheHill) {
  const sim::ScenarioRun run = sim::ExpandScenario("wilcox_slope", 1).at(0);
  const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  WilcoxOptions constant;
  constant.prior_fraction = 0.01;
  constant.prior_slip = 0.2;
  WilcoxOptions sloped = constant;
  sloped.prior_slip_per_slope = 1.0;
  const WilcoxScore flat = ScoreWilcox(log, EstimateWilcoxBaseline(log, constant));
  const WilcoxScore hill = ScoreWilcox(log, EstimateWilcoxBaseline(log, sloped));
  EXPECT_LT(hill.max_position_error_m, 0.5 * flat.max_position_error_m);
  EXPECT_LT(hill.odometry_error_fraction, 0.01);
}

// A user who knows neither the slip nor its slope: the 10 % prior starts at the paper's no-slip
// mean and learns the law from the terrain matching (wilcox_slope r1cm_run01: 0.204 and 0.964
// for the true 0.2 and 1; odometry error 2.2 -> 0.13 %).
TEST(WilcoxBaseline, LearnsTheSlipSlopeLawAsItDrives) {
  const sim::ScenarioRun run = sim::ExpandScenario("wilcox_slope", 1).at(0);
  const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  WilcoxOptions options;  // prior_slip 0, 10 %
  const WilcoxScore fixed = ScoreWilcox(log, EstimateWilcoxBaseline(log, options));
  options.learn_slip = true;
  const WilcoxResult learned = EstimateWilcoxBaseline(log, options);
  const WilcoxScore score = ScoreWilcox(log, learned);
  for (const WilcoxSide& side : learned.sides) {
    EXPECT_NEAR(side.law_slip, 0.2, 0.03) << side.side;
    EXPECT_NEAR(side.law_slip_per_slope, 1.0, 0.25) << side.side;
    EXPECT_GT(side.law_cycles_used, 50) << side.side;
  }
  EXPECT_LT(score.odometry_error_fraction, 0.5 * fixed.odometry_error_fraction);
  EXPECT_LT(score.odometry_error_fraction, 0.01);
}

// wilcoxm (docs/mismatch.md): slip correlated over distance around another mean, deeper ruts
// under the following wheels, a tilted ranging sensor. At 1 cm of roughness the learned prior
// (`sinkage`'s default) keeps the odometry error under the 1 % (seed 1, the first four
// runs: 0.32-0.54 %); on smooth ground (0.25 cm) the matching holds less (1.6-2.8 %), and the
// left/right check flags three of those four runs; one it passes is within 5 %.
TEST(WilcoxBaseline, OnWilcoxmTheLearnedPriorHoldsAtOneCentimetreAndSaysWhenItCannot) {
  WilcoxOptions options;
  options.learn_slip = true;
  int rough = 0, smooth = 0;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcoxm", 1)) {
    const bool one_cm = run.relative_directory.rfind("r1cm", 0) == 0;
    const bool quarter_cm = run.relative_directory.rfind("r0.25cm", 0) == 0;
    if (!(one_cm && rough < 4) && !(quarter_cm && smooth < 4)) continue;
    const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
    const WilcoxResult result = EstimateWilcoxBaseline(log, options);
    const WilcoxScore score = ScoreWilcox(log, result);
    std::printf("%s: odometry error %.2f %%, sides %s\n", run.relative_directory.c_str(),
                100.0 * score.odometry_error_fraction, result.sides_agree ? "agree" : "disagree");
    if (one_cm) {
      ++rough;
      EXPECT_LT(score.odometry_error_fraction, 0.01) << run.relative_directory;
    } else {
      ++smooth;
    }
    // Where the left/right check passes, the answer is good.
    if (result.sides_agree) {
      EXPECT_LT(score.odometry_error_fraction, 0.05) << run.relative_directory;
    }
  }
  EXPECT_EQ(rough, 4);
  EXPECT_EQ(smooth, 4);
}

// Two wilcoxm runs (1 cm, learned prior) whose rear wheel reaches ranged ground near cycle 17. A
// search that takes the map's ride height as exact there, but fits a free one for a candidate that
// leaves the rear wheel on the unranged start, favours "no advance" at that cycle and stays at it
// (odometry errors of 87 % and 44 %, the learned slip at 0.9). With one rule for every candidate
// the rover keeps moving on its map: measured 0.57 % and 0.71 %, bounded at 2 %, twice the issue's
// target for the suite's mean; no stop longer than two cycles while the rims turn (a stuck MAP
// stops for the rest of the run); the learned slip well below the 0.9 of a stuck run (the suite's
// slip means are 0.15-0.30, docs/mismatch.md).
TEST(WilcoxBaseline, AnEstimateThatStopsOnRangedGroundMovesOn) {
  WilcoxOptions options;
  options.learn_slip = true;
  const std::pair<uint64_t, const char*> runs[] = {{8, "r1cm_run05"}, {5, "r1cm_run02"}};
  int found = 0;
  for (const auto& [seed, name] : runs) {
    for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcoxm", seed)) {
      if (run.relative_directory != name) continue;
      ++found;
      const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
      const WilcoxResult result = EstimateWilcoxBaseline(log, options);
      EXPECT_LT(ScoreWilcox(log, result).odometry_error_fraction, 0.02) << seed << " " << name;
      for (const WilcoxSide& side : result.sides) {
        int stopped = 0, longest = 0;  // cycles in a row at zero advance with the rims turning
        for (const WilcoxCycle& c : side.cycles) {
          stopped = c.rim_m > 0.03 && c.advance_m < 0.001 ? stopped + 1 : 0;
          longest = std::max(longest, stopped);
        }
        EXPECT_LT(longest, 3) << seed << " " << name << " " << side.side;
        EXPECT_LT(side.law_slip, 0.45) << seed << " " << name << " " << side.side;
      }
    }
  }
  EXPECT_EQ(found, 2);  // both runs are still in the suite
}

}  // namespace
}  // namespace slipgraph
