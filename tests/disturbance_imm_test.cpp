// The Ward EKF as three disturbance modes (solvers/disturbance_imm.h): its mode probabilities,
// and against the single filter on mismatch runs whose velocity drifts off (a peaked tire law
// and a slowly wrong AHRS the model lacks; docs/mismatch.md) and on matched runs.
#include "solvers/disturbance_imm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "evaluation/evaluation.h"
#include "io/measurement_stream.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ekf_runner.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

Evaluation Suite(const std::vector<const char*>& names, uint64_t seed, bool modes) {
  std::vector<Evaluation> runs;
  for (const char* name : names) {
    const DriveLog log = testing::SimulatedScenario(name, seed);
    FilterRunOptions options;
    options.multiple_model = false;
    options.disturbance_modes = modes;
    const FilterResult result = RunEkf(log, DefaultModelConfig(log.vehicle), options);
    runs.push_back(Evaluate(log, EstimateTable(result.estimates)));
  }
  return Combine(runs, "runs");
}

TEST(DisturbanceImm, QuietWhileDrivingChangingAtAHoldBacksStart) {
  // ward21 seed 1 run 01: 0.75 m/s, held back from 9.59 s. Before it the robot drives on its
  // law (quiet); the hold-back's deceleration is a change the quiet mode cannot explain.
  const DriveLog log = testing::SimulatedScenario("ward21/01");
  ASSERT_EQ(log.events.size(), 1u);
  const double start = log.events[0].t_start;
  DisturbanceImm imm(log.vehicle, DefaultModelConfig(log.vehicle), EkfOptions{});
  double quiet_driving = 1.0, most_changed = 0.0, worst_sum_error = 0.0;
  testing::FeedStreams(log, &imm, {}, [&](const StreamEntry& e) {
    const double t = log.wheels[e.index].t;
    const auto& p = imm.probabilities();
    worst_sum_error = std::max(worst_sum_error, std::abs(p[0] + p[1] + p[2] - 1.0));
    for (double q : p) ASSERT_TRUE(q >= 0.0 && q <= 1.0);
    if (t > 5.0 && t < start - 0.5) {
      quiet_driving = std::min(quiet_driving, p[DisturbanceImm::kQuiet]);
    }
    if (t > start && t < start + 1.0) {
      most_changed =
          std::max(most_changed, p[DisturbanceImm::kChanging] + p[DisturbanceImm::kHeld]);
    }
  });
  std::printf("quiet while driving at least %.3f; changing or held at the start %.3f\n",
              quiet_driving, most_changed);
  EXPECT_LT(worst_sum_error, 1e-12);
  EXPECT_GT(quiet_driving, 0.5);
  EXPECT_GT(most_changed, 0.9);
}

// ward21m seed 2, runs 06 10 21, the runs GnssFadingPullsADriftingVelocityBack (ward_ekf_test)
// is tested on. Measured (2026-11-26): false immobilized 46.1 % of samples with one filter,
// 3.4 % with the modes; velocity RMSE 0.155 -> 0.051 m/s. What is left is run 10's false held
// disturbance after the surge that follows its stall (docs/mismatch.md). The control: three
// matched ward21 runs on the user's mean law (one filter, as --single-law): the same detections,
// no false alarm, velocity error within 50 % (measured 0.0166 -> 0.0206 m/s: the quiet mode holds
// v_bx at the mean law's slip, not the soil's).
TEST(DisturbanceImm, HoldsADriftingVelocityAtTheWheelsAndStillFindsHoldBacks) {
  const std::vector<const char*> drifting = {"ward21m/06", "ward21m/10", "ward21m/21"};
  const Evaluation one = Suite(drifting, 2, false), modes = Suite(drifting, 2, true);
  std::printf("ward21m seed 2, runs 06 10 21: false %.3f -> %.3f, v RMSE %.4f -> %.4f\n",
              one.false_immobilized_fraction(), modes.false_immobilized_fraction(),
              one.velocity_rmse, modes.velocity_rmse);
  EXPECT_GT(one.false_immobilized_fraction(), 0.2);
  EXPECT_LT(modes.false_immobilized_fraction(), 0.25 * one.false_immobilized_fraction());
  EXPECT_LT(modes.velocity_rmse, 0.5 * one.velocity_rmse);
  const std::vector<const char*> matched = {"ward21/01", "ward21/02", "ward21/03"};
  const Evaluation a = Suite(matched, 1, false), b = Suite(matched, 1, true);
  std::printf("ward21 seed 1, runs 01-03: detected %d -> %d, v RMSE %.4f -> %.4f\n", a.detected(),
              b.detected(), a.velocity_rmse, b.velocity_rmse);
  EXPECT_EQ(b.detected(), a.detected());
  EXPECT_EQ(b.false_immobilized_samples, 0);
  EXPECT_LT(b.velocity_rmse, 1.5 * a.velocity_rmse);
}

TEST(DisturbanceImmOptions, RejectsNonPositiveTimesAndSds) {
  DisturbanceImmOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.change_mean_s = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("change_mean_s"), std::string::npos);
  options = DisturbanceImmOptions();
  options.mix_interval_s = -1.0;
  EXPECT_FALSE(options.IsValid(&error));
}

}  // namespace
}  // namespace slipgraph
