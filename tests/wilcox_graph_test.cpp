// Wilcox's estimator as a factor graph: on the hand-made profile it recovers every advance to a
// fraction of a millimetre (the baseline: 7 mm); the suite figures are in docs/wilcox.md.
#include "solvers/wilcox_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "tests/wilcox_test_logs.h"

namespace slipgraph {
namespace {

using testing::HandMadeLog;
using testing::PointContact;

TEST(WilcoxGraph, RecoversAdvanceAndSinkageOnAHandMadeProfile) {
  const DriveLog log = HandMadeLog(0.003, 0.003);
  const WilcoxResult result = EstimateWilcoxGraph(log, PointContact());
  for (const WilcoxSide& side : result.sides) {
    ASSERT_EQ(side.cycles.size(), 40u);
    double worst = 0.0;
    for (const WilcoxCycle& c : side.cycles) worst = std::max(worst, std::abs(c.advance_m - 0.05));
    std::printf("%s: worst advance error %.5f m, total %.5f m\n", side.side.c_str(), worst,
                side.total_advance_m);
    EXPECT_LT(worst, 0.002);
    EXPECT_NEAR(side.total_advance_m, 2.0, 0.005);
  }
}

TEST(WilcoxGraph, SharedAdvanceOnTheHandMadeProfile) {
  WilcoxGraphOptions graph;
  graph.shared_advance = true;
  const WilcoxResult result = EstimateWilcoxGraph(HandMadeLog(0.003, 0.003), PointContact(), graph);
  ASSERT_EQ(result.sides.size(), 2u);
  for (size_t k = 0; k < result.sides[0].cycles.size(); ++k) {
    EXPECT_EQ(result.sides[0].cycles[k].advance_m, result.sides[1].cycles[k].advance_m);
    EXPECT_NEAR(result.sides[0].cycles[k].advance_m, 0.05, 0.002);
  }
}

TEST(WilcoxGraph, EndToEndOnSimulatedOneCentimetreRoughness) {
  // The first two simulated 1 cm runs, 10 % prior, against truth and against the paper's
  // sequential estimator on the same log. Measured (docs/wilcox.md, 8 runs): separate sides
  // 0.92 % mean (run 1 1.01 %, run 2 1.15 %), shared advance 0.45 % (0.34 %, 0.52 %), the paper's
  // 2.08 / 2.09 %; sinkage RMSE about 0.5-0.6 mm against 2 mm ranging noise.
  int runs = 0;
  double separate = 0.0, shared = 0.0;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox", 1)) {
    if (run.relative_directory.rfind("r1cm", 0) != 0) continue;
    if (++runs > 2) break;
    const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
    const WilcoxScore alone = ScoreWilcox(log, EstimateWilcoxGraph(log));
    WilcoxGraphOptions graph;
    graph.shared_advance = true;
    const WilcoxResult joint_result = EstimateWilcoxGraph(log, {}, graph);
    const WilcoxScore joint = ScoreWilcox(log, joint_result);
    // The baselines on the same log: the rim's own motion and the paper's sequential estimator.
    const WilcoxScore paper = ScoreWilcox(log, EstimateWilcoxBaseline(log));
    // Honest about its uncertainty: the front sinkage's marginal sd (covariance at the solution)
    // is the size of its error against truth (run 1: sd about 0.56 mm, RMSE 0.52 mm).
    double sd_sum = 0.0;
    int sd_count = 0;
    for (const WilcoxCycle& c : joint_result.sides[0].cycles) {
      ASSERT_TRUE(std::isfinite(c.advance_sd_m) && std::isfinite(c.sinkage_front_sd_m));
      sd_sum += c.sinkage_front_sd_m;
      ++sd_count;
    }
    const double mean_sd = sd_sum / sd_count;
    std::printf("mean sinkage sd %.2f mm against RMSE %.2f mm\n", 1000.0 * mean_sd,
                1000.0 * joint.sinkage_rmse_m);
    EXPECT_GT(mean_sd, 0.5 * joint.sinkage_rmse_m);
    EXPECT_LT(mean_sd, 2.0 * joint.sinkage_rmse_m);
    std::printf("%s: odometry error separate %.3f %%, shared %.3f %%; sinkage %.2f / %.2f mm\n",
                run.relative_directory.c_str(), 100.0 * alone.odometry_error_fraction,
                100.0 * joint.odometry_error_fraction, 1000.0 * alone.sinkage_rmse_m,
                1000.0 * joint.sinkage_rmse_m);
    EXPECT_LT(alone.odometry_error_fraction, 0.7 * paper.odometry_error_fraction);
    EXPECT_LT(joint.odometry_error_fraction, 0.35 * paper.odometry_error_fraction);
    EXPECT_LT(joint.odometry_error_fraction, 0.015);
    // The controls fail that bound: the paper's estimator (2.08 / 2.09 %) and the rim (24.7 /
    // 25.2 %).
    EXPECT_GT(paper.odometry_error_fraction, 0.015);
    EXPECT_GT(alone.rim_odometry_error_fraction, 0.2);
    EXPECT_LT(alone.sinkage_rmse_m, 0.004);  // twice the ranging noise
    EXPECT_LT(joint.sinkage_rmse_m, 0.004);
    separate += alone.odometry_error_fraction / 2.0;
    shared += joint.odometry_error_fraction / 2.0;
  }
  EXPECT_LT(shared, separate);
  EXPECT_LT(shared, 0.01);
}

TEST(WilcoxGraph, SlipInThePriorMeetsHalfAPercentAtOneCentimetre) {
  // The first two simulated 1 cm runs (20 % slip), 10 % prior, sides apart, with the prior's slip
  // learned as the rover drives (from the paper's 0) and with a fixed level slip of 0.2. Measured
  // (docs/wilcox.md): learned 0.46 / 0.10 %, fixed 0.23 / 0.11 % (8 runs: 0.21 / 0.13 % mean);
  // the no-slip prior 0.9 % mean. Before the search took the start's ride height out and the
  // profiles' own error in, a prior slip of 0.2 sent the start into a wrong minimum (15-39 %).
  int runs = 0;
  double learned = 0.0, fixed = 0.0;
  WilcoxGraphOptions graph;
  graph.covariance = false;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox", 1)) {
    if (run.relative_directory.rfind("r1cm", 0) != 0) continue;
    if (++runs > 2) break;
    const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
    WilcoxOptions learning;
    learning.learn_slip = true;
    const WilcoxResult learned_result = EstimateWilcoxGraph(log, learning, graph);
    const WilcoxScore learned_score = ScoreWilcox(log, learned_result);
    WilcoxOptions level;
    level.prior_slip = 0.2;
    const WilcoxScore fixed_score = ScoreWilcox(log, EstimateWilcoxGraph(log, level, graph));
    std::printf("%s: learned %.3f %% (law %.3f), fixed 0.2 %.3f %%\n",
                run.relative_directory.c_str(), 100.0 * learned_score.odometry_error_fraction,
                learned_result.sides[0].law_slip, 100.0 * fixed_score.odometry_error_fraction);
    EXPECT_LT(learned_score.odometry_error_fraction, 0.01);
    EXPECT_LT(fixed_score.odometry_error_fraction, 0.01);
    EXPECT_LT(learned_score.sinkage_rmse_m, 0.004);
    for (const WilcoxSide& side : learned_result.sides) EXPECT_NEAR(side.law_slip, 0.2, 0.03);
    learned += learned_score.odometry_error_fraction / 2.0;
    fixed += fixed_score.odometry_error_fraction / 2.0;
  }
  EXPECT_LT(learned, 0.005);
  EXPECT_LT(fixed, 0.005);
}

}  // namespace
}  // namespace slipgraph
