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
#include "tests/front_end_runs.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

Evaluation Suite(const std::vector<const char*>& names, uint64_t seed, bool modes) {
  FilterRunOptions options;
  options.multiple_model = false;
  options.disturbance_modes = modes;
  options.ekf.gnss_fading_fixes = 0.0;  // the modes alone, without the GNSS fading memory
  return testing::EvaluateFrontEnd(names, seed, options, UsePapersAccelBias);
}

TEST(DisturbanceImm, QuietWhileDrivingChangingAtAHoldBacksStart) {
  // ward21 seed 1 run 01: 0.75 m/s, held back from 9.59 s. Before it the robot drives on its
  // law (quiet); the hold-back's deceleration is a change the quiet mode cannot explain.
  const DriveLog log = testing::SimulatedScenario("ward21/01");
  ASSERT_EQ(log.events.size(), 1u);
  const double start = log.events[0].t_start;
  DisturbanceImm imm(log.vehicle, DefaultModelConfig(log.vehicle), EkfOptions{});
  double quiet_driving = 1.0, most_changed = 0.0;
  bool all_finite = true;
  testing::FeedStreams(log, &imm, {}, [&](const StreamEntry& e) {
    const double t = log.wheels[e.index].t;
    const Eigen::VectorXd& p = imm.probabilities();
    all_finite = all_finite && p.allFinite() && std::abs(p.sum() - 1.0) < 1e-12;
    if (t > 5.0 && t < start - 0.5) {
      quiet_driving = std::min(quiet_driving, p(DisturbanceImm::kQuiet));
    }
    if (t > start && t < start + 1.0) {
      most_changed = std::max(most_changed, 1.0 - p(DisturbanceImm::kQuiet));
    }
  });
  std::printf("quiet while driving at least %.3f; changing or held at the start %.3f\n",
              quiet_driving, most_changed);
  EXPECT_TRUE(all_finite);
  EXPECT_GT(quiet_driving, 0.5);
  EXPECT_GT(most_changed, 0.9);
}

// ward21m seed 2, runs 06 10 21, the runs GnssFadingPullsADriftingVelocityBack (ward_ekf_test)
// is tested on, with the paper's accelerometer bias walk. Measured: false immobilized 44.4 % of
// samples with one filter, 0.0 % with the modes; velocity RMSE 0.155 -> 0.037 m/s. The control:
// three matched ward21 runs on the user's mean law (one filter, as --single-law): the same
// detections, no false alarm, velocity error within 50 % (measured 0.0173 -> 0.0216 m/s: the
// quiet mode holds v_bx at the mean law's slip, not the soil's).
TEST(DisturbanceImm, HoldsADriftingVelocityAtTheWheelsAndStillFindsHoldBacks) {
  const std::vector<const char*> drifting = {"ward21m/06", "ward21m/10", "ward21m/21"};
  const Evaluation one = Suite(drifting, 2, false), modes = Suite(drifting, 2, true);
  std::printf("ward21m seed 2, runs 06 10 21: false %.3f -> %.3f, v RMSE %.4f -> %.4f\n",
              one.false_immobilized_fraction(), modes.false_immobilized_fraction(),
              one.velocity_rmse, modes.velocity_rmse);
  EXPECT_GT(one.false_immobilized_fraction(), 0.2);
  EXPECT_LT(modes.false_immobilized_fraction(), 0.15 * one.false_immobilized_fraction());
  EXPECT_LT(modes.velocity_rmse, 0.5 * one.velocity_rmse);
  const std::vector<const char*> matched = {"ward21/01", "ward21/02", "ward21/03"};
  const Evaluation a = Suite(matched, 1, false), b = Suite(matched, 1, true);
  std::printf("ward21 seed 1, runs 01-03: detected %d -> %d, v RMSE %.4f -> %.4f\n", a.detected(),
              b.detected(), a.velocity_rmse, b.velocity_rmse);
  EXPECT_EQ(b.detected(), a.detected());
  EXPECT_EQ(b.false_immobilized_samples, 0);
  EXPECT_LT(b.velocity_rmse, 1.5 * a.velocity_rmse);
}

TEST(ImmArithmetic, TransitionOverAnIntervalByHand) {
  // Three modes: 0 -> 1 at 0.5/s; 1 -> 0 and 1 -> 2 at 1/s each; 2 -> 1 at 0.1/s.
  Eigen::MatrixXd rate = Eigen::MatrixXd::Zero(3, 3);
  rate(0, 1) = 0.5;
  rate(1, 0) = rate(1, 2) = 1.0;
  rate(2, 1) = 0.1;
  const Eigen::MatrixXd T = imm::Transition(rate, 0.25);
  EXPECT_NEAR(T(0, 0), std::exp(-0.125), 1e-15);
  EXPECT_NEAR(T(0, 1), 1.0 - std::exp(-0.125), 1e-15);
  EXPECT_EQ(T(0, 2), 0.0);
  EXPECT_NEAR(T(1, 1), std::exp(-0.5), 1e-15);
  EXPECT_NEAR(T(1, 0), 0.5 * (1.0 - std::exp(-0.5)), 1e-15);
  EXPECT_NEAR(T(1, 2), T(1, 0), 1e-15);
  EXPECT_NEAR(T(2, 1), 1.0 - std::exp(-0.025), 1e-15);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(T.row(i).sum(), 1.0, 1e-15);
  EXPECT_TRUE(imm::Transition(rate, 0.0).isIdentity());
}

TEST(ImmArithmetic, PosteriorByHandWithoutUnderflowAndWithNan) {
  Eigen::VectorXd predicted(3), log_likelihood(3);
  predicted << 0.5, 0.3, 0.2;
  log_likelihood << std::log(0.1), std::log(0.4), std::log(0.2);
  Eigen::VectorXd expected(3);
  expected << 0.05, 0.12, 0.04;
  expected /= expected.sum();
  EXPECT_TRUE(imm::Posterior(predicted, log_likelihood).isApprox(expected, 1e-14));
  // Log-likelihoods far below exp's range (a long interval's sum) change nothing but scale.
  EXPECT_TRUE(imm::Posterior(predicted, log_likelihood.array() - 5000.0)
                  .matrix()
                  .isApprox(expected, 1e-12));
  // The best likelihood in a mode the chain cannot be in: the others still share the rest.
  predicted << 0.6, 0.4, 0.0;
  log_likelihood << -900.0, -901.0, 0.0;
  const Eigen::VectorXd p = imm::Posterior(predicted, log_likelihood);
  EXPECT_NEAR(p(0), 0.6 / (0.6 + 0.4 * std::exp(-1.0)), 1e-12);
  EXPECT_EQ(p(2), 0.0);
  // A NaN is impossible; nothing finite leaves the prediction.
  log_likelihood << std::nan(""), -1.0, -1.0;
  EXPECT_EQ(imm::Posterior(predicted, log_likelihood)(0), 0.0);
  log_likelihood << std::nan(""), std::nan(""), std::nan("");
  EXPECT_EQ(imm::Posterior(predicted, log_likelihood), predicted);
}

TEST(ImmArithmetic, MixtureMomentsByHand) {
  // Two states 0.1 and 0.3 m/s with variances 0.01 and 0.04, weights 0.25 and 0.75: mean 0.25,
  // variance 0.25 0.01 + 0.75 0.04 + 0.25 0.15^2 + 0.75 0.05^2 = 0.0325 + 0.0075 = 0.04.
  ekf::StateVector a = ekf::StateVector::Zero(), b = ekf::StateVector::Zero();
  a(ward::kVbx) = 0.1;
  b(ward::kVbx) = 0.3;
  ekf::StateMatrix Pa = 0.01 * ekf::StateMatrix::Identity();
  ekf::StateMatrix Pb = 0.04 * ekf::StateMatrix::Identity();
  ekf::StateVector mean;
  ekf::StateMatrix covariance;
  imm::MixtureMoments({0.25, 0.75}, {&a, &b}, {&Pa, &Pb}, &mean, &covariance);
  EXPECT_NEAR(mean(ward::kVbx), 0.25, 1e-15);
  EXPECT_NEAR(covariance(ward::kVbx, ward::kVbx), 0.04, 1e-15);
  EXPECT_NEAR(covariance(ward::kAdist, ward::kAdist), 0.0325, 1e-15);  // no spread there
  EXPECT_EQ(covariance(ward::kVbx, ward::kAdist), 0.0);
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
