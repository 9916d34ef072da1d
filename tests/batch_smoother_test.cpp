// The batch smoother end to end on simulated logs, and its fall-back to the EKF.
#include "solvers/batch_smoother.h"

#include <gtest/gtest.h>

#include "evaluation/evaluation.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace {

DriveLog Simulated(const std::string& scenario) {
  const sim::ScenarioRun run = sim::ExpandScenario(scenario, 1).at(0);
  DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  log.directory = scenario;
  return log;
}


TEST(BatchSmoother, Fig5IsSmoothedWithUncertaintyAndTheHoldBackFound) {
  const DriveLog log = Simulated("fig5");
  const SmootherResult result = SmoothBatch(log, DefaultModelConfig(log.vehicle));
  ASSERT_FALSE(result.used_fallback);
  EXPECT_TRUE(result.summary.IsSolutionUsable());
  EXPECT_TRUE(result.covariance_ok);
  ASSERT_EQ(result.estimates.size(), log.wheels.size());
  for (const EkfEstimate& e : result.estimates) {
    for (double sd : e.sd) EXPECT_GT(sd, 0.0);
  }
  const Evaluation ev = Evaluate(log, EstimateTable(result.estimates));
  EXPECT_EQ(ev.detected(), 1);
  EXPECT_EQ(ev.false_immobilized_samples, 0);
  // Measured 0.028 m/s (the EKF: 0.020): the smoother does not beat the filter yet
  // (docs/smoother.md); this bound guards against it getting worse.
  EXPECT_LT(ev.velocity_rmse, 0.04);
}

TEST(BatchSmoother, FallsBackToTheEkfAndSaysSo) {
  // A log with a single wheel sample cannot make a chain of states.
  DriveLog log = Simulated("fig5");
  log.wheels.resize(1);
  const SmootherResult result = SmoothBatch(log, DefaultModelConfig(log.vehicle));
  EXPECT_TRUE(result.used_fallback);
  ASSERT_FALSE(result.notes.empty());
  EXPECT_EQ(result.estimates.size(), result.ekf.estimates.size());
}

}  // namespace
}  // namespace slipgraph
