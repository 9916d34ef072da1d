// The model beside the measurements on a simulated log whose model is right (fig5): every stream
// is there, its normalized residuals are of their stated size and belong to states that exist;
// the path distance grows with the drive to the truth's length; a solution of another log is
// refused.
#include "workbench/model_residuals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "solvers/batch_smoother.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

TEST(ModelResiduals, EveryStreamThereWithResidualsOfTheirSize) {
  const DriveLog log = testing::SimulatedScenario("fig5");
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  const SmootherResult solution = SmoothBatch(log, model);
  ASSERT_FALSE(solution.used_fallback);
  const ModelResiduals m = EvaluateModelResiduals(log, model, solution);
  ASSERT_EQ(m.states.size(), log.wheels.size());
  for (const char* name : {"accelerometer", "gyro", "encoder_left", "encoder_right", "gnss"}) {
    const StreamResiduals* s = m.Find(name);
    ASSERT_NE(s, nullptr) << name;
    ASSERT_GT(s->normalized.size(), 10u) << name;
    ASSERT_EQ(s->t.size(), s->normalized.size());
    ASSERT_EQ(s->state.size(), s->normalized.size());
    double sum2 = 0.0;
    for (size_t i = 0; i < s->normalized.size(); ++i) {
      ASSERT_TRUE(std::isfinite(s->normalized[i])) << name << " " << i;
      ASSERT_GT(s->sd[i], 0.0);
      ASSERT_LT(s->state[i], m.states.size());
      sum2 += s->normalized[i] * s->normalized[i];
    }
    const double variance = sum2 / s->normalized.size();
    std::printf("%s: %zu residuals, variance %.4f\n", name, s->normalized.size(), variance);
    EXPECT_LT(variance, 3.0) << name;
    // The encoders and GNSS near one. Not the accelerometer, whose sd holds the tire law's stated
    // uncertainty (30 % of the traction: the law is exact here), nor the gyro, which the yaw rate
    // follows sample by sample (each residual's leverage is near one).
    const std::string n = name;
    if (n != "accelerometer" && n != "gyro") {
      EXPECT_GT(variance, 0.3) << name;
    }
  }
  EXPECT_EQ(m.Find("compass"), nullptr);
}

TEST(ModelResiduals, PathDistanceFollowsTheDrive) {
  const DriveLog log = testing::SimulatedScenario("fig5");
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  const ModelResiduals m = EvaluateModelResiduals(log, model, SmoothBatch(log, model));
  const std::vector<double> s = PathDistances(m);
  ASSERT_EQ(s.size(), m.states.size());
  for (size_t k = 1; k < s.size(); ++k) ASSERT_GE(s[k], s[k - 1]);
  double truth = 0.0;
  for (size_t i = 1; i < log.truth.size(); ++i) {
    truth += std::abs(log.truth[i].vx) * (log.truth[i].t - log.truth[i - 1].t);
  }
  EXPECT_NEAR(s.back(), truth, 0.02 * truth);
}

TEST(ModelResiduals, ASolutionOfAnotherLogIsRefused) {
  const DriveLog log = testing::SimulatedScenario("fig5");
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  SmootherResult solution = SmoothBatch(log, model);
  solution.estimates.pop_back();
  EXPECT_THROW(EvaluateModelResiduals(log, model, solution), std::invalid_argument);
}

}  // namespace
}  // namespace slipgraph
