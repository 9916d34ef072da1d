// The IPD identification EKF end to end on simulated tracked-vehicle logs: it recovers a known
// slip model on one terrain, and on ipd35 it beats the no-slip model by the paper's margins
// (the full figures are in docs/ipd.md).
#include "solvers/ipd_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ipd_graph_calibration.h"
#include "tests/estimate_check.h"

namespace slipgraph {
namespace {

DriveLog SimulateIpd(double minutes, const std::string& terrain) {
  sim::Scenario sc = sim::ExpandScenario("ipd35", 1).at(0).scenario;
  if (!terrain.empty()) sc.course.patches = {{0.0, sim::FindTerrain(terrain)}};
  double total = sc.rest_start_s;
  size_t keep = 0;
  while (keep < sc.commands.size() && total < minutes * 60.0)
    total += sc.commands[keep++].duration_s;
  sc.commands.resize(keep);
  DriveLog log = sim::Simulate(sc, 7).log;
  log.directory = "ipd";
  return log;
}

TEST(IpdCalibration, RecoversAKnownSlipModelOnOneTerrain) {
  const DriveLog log = SimulateIpd(8.0, "loose_rock");
  const IpdCalibrationResult result = CalibrateIpdEkf(log);
  const std::array<double, 13>& truth = sim::FindTerrain("loose_rock").ipd.alpha;
  // The parameters the drive excites well (forward slip with speed, yaw gain, lateral skid in
  // turns): within 20 % of truth, sd under 0.01, error within 3 sd (measured: alpha 0 -0.063 +-
  // 0.005 for -0.070, alpha 9 -0.264 +- 0.005 for -0.250, 2.7 sd: that sd is on the tight side).
  for (int i : {0, 9}) {
    EXPECT_TRUE(testing::EstimateOf(result.final_alpha[i], result.final_alpha_sd[i], truth[i],
                                    0.2 * std::abs(truth[i]), 0.01))
        << "alpha " << i;
  }
  const PredictionStats no_slip = Summarize(result.no_slip);
  const PredictionStats calibrated = Summarize(result.calibrated);
  EXPECT_LT(calibrated.mean_position_error_m, 0.4 * no_slip.mean_position_error_m);
  EXPECT_LT(calibrated.mean_heading_error_rad, 0.3 * no_slip.mean_heading_error_rad);
}

// A 6-minute drive from `before` to `after` at 150 m of signed travel, and the time it crosses.
struct TwoTerrainLog {
  DriveLog log;
  double t_boundary = -1.0;
};
TwoTerrainLog SimulateTwoTerrains(const std::string& before, const std::string& after) {
  sim::Scenario sc = sim::ExpandScenario("ipd35", 1).at(0).scenario;
  sc.course.patches = {{0.0, sim::FindTerrain(before)}, {150.0, sim::FindTerrain(after)}};
  double total = sc.rest_start_s;
  size_t keep = 0;
  while (keep < sc.commands.size() && total < 6.0 * 60.0) total += sc.commands[keep++].duration_s;
  sc.commands.resize(keep);
  TwoTerrainLog r;
  r.log = sim::Simulate(sc, 11).log;
  double s = 0.0;
  for (size_t k = 1; k < r.log.truth.size() && r.t_boundary < 0.0; ++k) {
    s += r.log.truth[k].vx * (r.log.truth[k].t - r.log.truth[k - 1].t);
    if (s >= 150.0) r.t_boundary = r.log.truth[k].t;
  }
  return r;
}

// The batch's Q by maximum likelihood (solvers/ipd_noise_likelihood.h) on one soil: the same Q
// as the paper's online stochastic calibration (the EKF's, eqs. 18-27) within 20 % on every
// axis (measured 0.98 / 0.99 / 0.86 of it; both put the forward noise at 0.68 of the simulator's
// stated density on this soil, so neither is compared with that). And from asphalt to mud it
// follows the soil: the simulator's mud is 4 x as noisy on every axis.
TEST(IpdCalibration, BatchNoiseByLikelihoodFollowsTheSoil) {
  const DriveLog log = SimulateIpd(8.0, "loose_rock");
  const IpdCalibrationResult batch = CalibrateIpdBatch(log);
  const IpdCalibrationResult ekf = CalibrateIpdEkf(log);
  ASSERT_FALSE(batch.q.empty());
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& q : batch.q) mean += q;
  mean /= static_cast<double>(batch.q.size());
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(mean[j] / ekf.final_q[j], 1.0, 0.2) << "q " << j << ": " << mean[j];
  }

  const TwoTerrainLog two = SimulateTwoTerrains("asphalt", "mud");
  const IpdCalibrationResult changed = CalibrateIpdBatch(two.log);
  Eigen::Vector3d before = Eigen::Vector3d::Zero(), after = Eigen::Vector3d::Zero();
  int n_before = 0, n_after = 0;
  for (size_t b = 0; b < changed.q.size(); ++b) {
    // Blocks 30 s or more from the change (the walk on log q spreads it over about that).
    if (changed.update_t[b] < two.t_boundary - 30.0) {
      before += changed.q[b];
      ++n_before;
    } else if (changed.update_t[b] > two.t_boundary + 30.0) {
      after += changed.q[b];
      ++n_after;
    }
  }
  ASSERT_GT(n_before, 0);
  ASSERT_GT(n_after, 0);
  for (int j = 0; j < 3; ++j) {
    EXPECT_GT(after[j] / n_after, 2.0 * before[j] / n_before) << "q " << j;
  }
}

// Mean position error of the predictions starting within `seconds` after t.
double ErrorAfter(const IpdCalibrationResult& r, double t, double seconds) {
  double sum = 0.0;
  int n = 0;
  for (const PredictionError& e : r.calibrated) {
    if (e.t_start > t && e.t_start < t + seconds) {
      sum += std::hypot(e.along_m, e.cross_m);
      ++n;
    }
  }
  return sum / n;
}

// A terrain change is a jump in alpha that the slow random walk cannot follow. Asphalt to mud
// is large enough that segments fail the gate: taken with alpha's covariance inflated (the
// re-admission) or found by the jump detector, the model is back on the new terrain sooner.
TEST(IpdCalibration, FollowsAJumpInTheSlipModel) {
  const TwoTerrainLog two = SimulateTwoTerrains("asphalt", "mud");
  ASSERT_GT(two.t_boundary, 0.0);
  const auto error_after = [&](const IpdCalibrationResult& r) {
    return ErrorAfter(r, two.t_boundary, 30.0);
  };
  const DriveLog& log = two.log;
  IpdOptions neither, gate_only, detector_only;
  neither.readmit_after = 0;
  neither.jump.enabled = false;
  gate_only.jump.enabled = false;
  detector_only.readmit_after = 0;
  const IpdCalibrationResult with = CalibrateIpdEkf(log), without = CalibrateIpdEkf(log, neither);
  const double error_with = error_after(with), error_without = error_after(without);
  std::printf("after the change: EKF %.3f, gate only %.3f, detector only %.3f, neither %.3f m\n",
              error_with, error_after(CalibrateIpdEkf(log, gate_only)),
              error_after(CalibrateIpdEkf(log, detector_only)), error_without);
  EXPECT_LT(error_with, 0.8 * error_without) << error_with << " vs " << error_without;
  ASSERT_FALSE(with.notes.empty());
  // The Ceres window's counterpart: the walk into the block where segments fail the gate in a
  // row is freed (a jump). Measured here with 0.5 s blocks: 0.134 against 0.215 m without it
  // (0.203 against 0.223 with the earlier 5 s blocks).
  IpdGraphOptions no_jump;
  no_jump.jump_sd = 0.0;
  const IpdCalibrationResult window = CalibrateIpdWindow(log);
  const IpdCalibrationResult window_without = CalibrateIpdWindow(log, IpdOptions{}, no_jump);
  std::printf("after the change: window %.3f, without the jump %.3f m\n", error_after(window),
              error_after(window_without));
  EXPECT_LT(error_after(window), 0.95 * error_after(window_without))
      << error_after(window) << " vs " << error_after(window_without);
}

// Soft dirt to asphalt: forward slip -0.10 -> -0.02 and the yaw gain -0.20 -> -0.08, errors of
// 10-15 cm where the prediction's sd is about 5: few segments past the gate, so the
// re-admission alone follows it slowly; the jump detector (solvers/jump_detector.h) finds it
// from the run of innovations.
TEST(IpdCalibration, FindsATerrainChangeTheGateMisses) {
  const TwoTerrainLog two = SimulateTwoTerrains("soft_dirt", "asphalt");
  ASSERT_GT(two.t_boundary, 0.0);
  IpdOptions gate_only;
  gate_only.jump.enabled = false;
  const IpdCalibrationResult with = CalibrateIpdEkf(two.log);
  const IpdCalibrationResult without = CalibrateIpdEkf(two.log, gate_only);
  const IpdCalibrationResult window = CalibrateIpdWindow(two.log);
  IpdOptions window_gate_only;
  window_gate_only.jump.enabled = false;
  const IpdCalibrationResult window_without = CalibrateIpdWindow(two.log, window_gate_only);
  for (double seconds : {10.0, 30.0}) {
    std::printf("%.0f s after the change: EKF %.3f, gate only %.3f; window %.3f, gate only %.3f\n",
                seconds, ErrorAfter(with, two.t_boundary, seconds),
                ErrorAfter(without, two.t_boundary, seconds),
                ErrorAfter(window, two.t_boundary, seconds),
                ErrorAfter(window_without, two.t_boundary, seconds));
  }
  // Measured: 10 s after, EKF 0.114 against 0.126 m, window 0.113 against 0.122; 30 s after,
  // 0.076 against 0.083 and 0.075 against 0.079.
  EXPECT_LT(ErrorAfter(with, two.t_boundary, 10.0),
            0.95 * ErrorAfter(without, two.t_boundary, 10.0));
  EXPECT_LT(ErrorAfter(window, two.t_boundary, 10.0),
            0.95 * ErrorAfter(window_without, two.t_boundary, 10.0));
  bool noted = false;
  for (const std::string& note : with.notes) noted |= note.find("jump(s)") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(IpdCalibration, Ipd35BeatsTheNoSlipModel) {
  const DriveLog log = SimulateIpd(35.0, "");
  const IpdCalibrationResult result = CalibrateIpdEkf(log);
  // The Ceres forms on the same log: the online window at least as good as the EKF, the batch
  // (not causal) better.
  const IpdCalibrationResult window_result = CalibrateIpdWindow(log);
  const PredictionStats window = Summarize(window_result.calibrated);
  const PredictionStats batch = Summarize(CalibrateIpdBatch(log).calibrated);
  const PredictionStats no_slip = Summarize(result.no_slip);
  const PredictionStats calibrated = Summarize(result.calibrated);
  // Measured (docs/ipd.md): 0.295 -> 0.071 m, heading 0.311 -> 0.044 rad, sd along 0.112 ->
  // 0.054 (the simulator's own slip model gets 0.045), cross 0.263 -> 0.073 m; predicted /
  // sample variance after the first minute 1.12, 1.07, 0.83 with the covariance matching (0.88,
  // 0.83, 0.54 without); on this test's log 1.11, 1.05, 0.91.
  EXPECT_LT(calibrated.mean_position_error_m, 0.32 * no_slip.mean_position_error_m);    // 68 %
  EXPECT_LT(calibrated.sd_cross_m, 0.4 * no_slip.sd_cross_m);                           // 60 %
  EXPECT_LT(calibrated.mean_heading_error_rad, 0.17 * no_slip.mean_heading_error_rad);  // 83 %
  EXPECT_LT(calibrated.sd_along_m, 0.55 * no_slip.sd_along_m);  // the paper's 60 % is not reached
  const PredictionStats late = Summarize(AfterTheFirstMinute(result.calibrated));
  std::printf("predicted / sample variance after the first minute: %.2f %.2f %.2f\n",
              late.predicted_over_sample[0], late.predicted_over_sample[1],
              late.predicted_over_sample[2]);
  for (int i = 0; i < 3; ++i) {  // the 20 %, heading included since the matching
    EXPECT_GT(late.predicted_over_sample[i], 0.8);
    EXPECT_LT(late.predicted_over_sample[i], 1.2);
  }
  // The batch's Q by maximum likelihood per block (solvers/ipd_noise_likelihood.h), then its
  // covariance matching (which only inflates): its predicted covariance within the 20 %
  // on every axis (the EKF's final Q for the whole log, before the matching, gave 1.09 / 1.28
  // along / cross here, 0.67 / 0.59 / 0.46 on seed 4). Q alone is checked in
  // BatchNoiseByLikelihoodFollowsTheSoil.
  std::printf("batch: %.2f %.2f %.2f\n", batch.predicted_over_sample[0],
              batch.predicted_over_sample[1], batch.predicted_over_sample[2]);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(batch.predicted_over_sample[i], 0.8);
    EXPECT_LT(batch.predicted_over_sample[i], 1.2);
  }
  std::printf("mean position error EKF %.4f window %.4f batch %.4f m; heading %.4f %.4f rad\n",
              calibrated.mean_position_error_m, window.mean_position_error_m,
              batch.mean_position_error_m, calibrated.mean_heading_error_rad,
              window.mean_heading_error_rad);
  // The window at least as good as the EKF (ipd35 seeds 1-3: 0.0703 / 0.0692 / 0.0690 against
  // 0.0709 / 0.0698 / 0.0695 m; docs/ipd.md).
  EXPECT_LE(window.mean_position_error_m, calibrated.mean_position_error_m);
  EXPECT_LE(window.mean_heading_error_rad, 1.02 * calibrated.mean_heading_error_rad);
  const Eigen::Vector3d window_ratio =
      Summarize(AfterTheFirstMinute(window_result.calibrated)).predicted_over_sample;
  std::printf("window: %.2f %.2f %.2f\n", window_ratio[0], window_ratio[1], window_ratio[2]);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(window_ratio[i], 0.8);
    EXPECT_LT(window_ratio[i], 1.2);
  }
  EXPECT_LT(batch.mean_position_error_m, calibrated.mean_position_error_m);
}

// ipd35m (docs/mismatch.md): the tracks' slip from the soil's shear, which the 13-parameter
// model only approximates. The bound: the mean 2-s prediction error at least 60 % below
// the no-slip model's; the paper's heading sd reduction (71 %) for the batch.
TEST(IpdCalibration, Ipd35mBeatsTheNoSlipModelWithoutTheSlipModelInItsTruth) {
  const sim::ScenarioRun run = sim::ExpandScenario("ipd35m", 1).at(0);
  DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  log.directory = "ipd35m";
  const IpdCalibrationResult ekf = CalibrateIpdEkf(log);
  const PredictionStats no_slip = Summarize(ekf.no_slip);
  const PredictionStats filtered = Summarize(ekf.calibrated);
  const IpdCalibrationResult batch_result = CalibrateIpdBatch(log);
  const PredictionStats batch = Summarize(batch_result.calibrated);
  std::printf(
      "ipd35m seed 1: position %.4f -> ekf %.4f, batch %.4f m; sd heading %.4f -> %.4f, "
      "%.4f rad\n",
      no_slip.mean_position_error_m, filtered.mean_position_error_m, batch.mean_position_error_m,
      no_slip.sd_heading_rad, filtered.sd_heading_rad, batch.sd_heading_rad);
  EXPECT_LT(filtered.mean_position_error_m, 0.4 * no_slip.mean_position_error_m);
  EXPECT_LT(batch.mean_position_error_m, 0.4 * no_slip.mean_position_error_m);
  EXPECT_LT(batch.sd_heading_rad, 0.29 * no_slip.sd_heading_rad);
  // The batch's heading errors outgrow its predicted variance in tight turns at low speed, where
  // the 13-parameter model's yaw slip is biased; its covariance matching takes back part of it
  // (after the first minute 0.32 -> 0.59 on this seed; over 20 seeds in docs/mismatch.md) and
  // leaves along and cross conservative within 30 %.
  const Eigen::Vector3d ratio =
      Summarize(AfterTheFirstMinute(batch_result.calibrated)).predicted_over_sample;
  std::printf("batch, predicted / sample variance after the first minute: %.2f %.2f %.2f\n",
              ratio[0], ratio[1], ratio[2]);
  EXPECT_GT(ratio[2], 0.5);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(ratio[i], 0.9);
    EXPECT_LT(ratio[i], 1.3);
  }
}

}  // namespace
}  // namespace slipgraph
