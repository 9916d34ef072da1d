// RunEkf: the front end over a whole log. Here the tire law's slope uncertainty in its sd
// (ModelConfig::tire_slip_stiffness_relative_sd, a consider covariance): on mismatch runs, whose
// truth has a tire law of another family (docs/mismatch.md), the sd grow where the estimate leans
// on the law and the velocity error falls inside its bound far more often; the estimates do not
// move; a bank of filters carries the law's uncertainty in its spread and is left as it is.
#include "solvers/ekf_runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "evaluation/evaluation.h"
#include "io/estimate_file.h"
#include "tests/front_end_runs.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

bool HasNote(const FilterResult& result, const std::string& text) {
  return std::any_of(result.notes.begin(), result.notes.end(),
                     [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

// ward21m seed 1, runs 01-06 (seeds 1-10 chose 0.7, the default: docs/mismatch.md): the share of
// samples inside the 95 % bound, single filter with GNSS, the law as exact and as a guess.
TEST(EkfRunner, TheLawsSlopeUncertaintyWidensTheSdNotTheEstimate) {
  std::vector<Evaluation> plain_runs, considered_runs;
  for (const char* name :
       {"ward21m/01", "ward21m/02", "ward21m/03", "ward21m/04", "ward21m/05", "ward21m/06"}) {
    const DriveLog log = testing::SimulatedScenario(name);
    ModelConfig model = DefaultModelConfig(log.vehicle);
    UsePapersAccelBias(&model);
    ASSERT_TRUE(model.law_samples.empty());
    // A law nobody fitted to this terrain is a guess by default.
    EXPECT_EQ(model.tire_slip_stiffness_relative_sd, 0.7);
    const FilterResult considered = RunEkf(log, model);
    model.tire_slip_stiffness_relative_sd = 0.0;  // the law as exact
    const FilterResult plain = RunEkf(log, model);
    EXPECT_TRUE(HasNote(considered, "slope uncertainty")) << name;
    ASSERT_EQ(plain.estimates.size(), considered.estimates.size());
    // The law's share, for a window behind it to add to its own sd.
    ASSERT_EQ(considered.law_spread_sd.size(), considered.estimates.size());
    EXPECT_TRUE(std::any_of(considered.law_spread_sd.begin(), considered.law_spread_sd.end(),
                            [](const auto& share) { return share[ward::kVbx] > 0.0; }));
    for (size_t k = 0; k < plain.estimates.size(); ++k) {
      for (int i = 0; i < ward::kStateSize; ++i) {
        ASSERT_EQ(plain.estimates[k].x[i], considered.estimates[k].x[i]) << name << " " << k;
        ASSERT_GE(considered.estimates[k].sd[i], plain.estimates[k].sd[i]) << name << " " << k;
      }
    }
    plain_runs.push_back(Evaluate(log, EstimateTable(plain.estimates)));
    considered_runs.push_back(Evaluate(log, EstimateTable(considered.estimates)));
  }
  const double before = Combine(plain_runs, "plain").nees_within_95_fraction();
  const double after = Combine(considered_runs, "considered").nees_within_95_fraction();
  std::printf("ward21m seed 1, runs 01-06: v NEES inside 95 %% %.3f -> %.3f\n", before, after);
  // Measured: 0.640 -> 0.908, with the paper's accelerometer bias walk (which leaves the velocity
  // drifting further than its sd on these runs; docs/mismatch.md).
  EXPECT_LT(before, 0.7);
  EXPECT_GT(after, before + 0.25);
}

// ward21/01 lists the soils its law was fitted over: the bank runs, its sd unchanged.
TEST(EkfRunner, TheBankKeepsItsOwnSpread) {
  const DriveLog log = testing::SimulatedScenario("ward21/01");
  ModelConfig model = DefaultModelConfig(log.vehicle);
  ASSERT_GE(model.law_samples.size(), 2u);
  model.tire_slip_stiffness_relative_sd = 0.0;
  const FilterResult plain = RunEkf(log, model);
  model.tire_slip_stiffness_relative_sd = 0.7;
  const FilterResult considered = RunEkf(log, model);
  EXPECT_TRUE(HasNote(considered, "bank's spread"));
  ASSERT_EQ(plain.estimates.size(), considered.estimates.size());
  for (size_t k = 0; k < plain.estimates.size(); k += 53) {
    EXPECT_EQ(plain.estimates[k].sd[ward::kVbx], considered.estimates[k].sd[ward::kVbx]);
  }
}

// The disturbance's density each prediction took, one per estimate, for a smoother behind the
// filter: the model's w3 where the accelerometer agrees with the model, up to the cap where it
// does not (a hold-back's onset), for one filter and for the bank.
TEST(EkfRunner, ReportsTheAdaptiveDisturbanceDensity) {
  const DriveLog log = testing::SimulatedScenario("ward21/01");
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  const ProcessNoiseConfig& q = model.process;
  FilterRunOptions single;
  single.multiple_model = false;
  for (const FilterRunOptions& options : {FilterRunOptions{}, single}) {
    const FilterResult result = RunEkf(log, model, options);
    ASSERT_EQ(result.disturbance_density.size(), result.estimates.size());
    const auto [low, high] =
        std::minmax_element(result.disturbance_density.begin(), result.disturbance_density.end());
    std::printf("w3 from %.2f to %.2f\n", *low, *high);
    EXPECT_NEAR(*low, q.a_dist_mps3_per_sqrt_hz, 1e-9);
    EXPECT_GT(*high, 2.0 * q.a_dist_mps3_per_sqrt_hz);
    EXPECT_LE(*high, q.a_dist_max_mps3_per_sqrt_hz + 1e-9);
  }
  // The disturbance modes: a drive starts in the quiet mode, at its driving density; after that
  // the modes' densities weighed, between the held mode's slow walk and the largest adaptive w3.
  FilterRunOptions modes = single;
  modes.disturbance_modes = true;
  const DisturbanceImmOptions& imm = modes.disturbance_modes_options;
  const FilterResult result = RunEkf(log, model, modes);
  ASSERT_EQ(result.disturbance_density.size(), result.estimates.size());
  EXPECT_NEAR(result.disturbance_density.front(),
              imm.quiet_a_dist_sd_mps2 / ward::GaussMarkovStationarySd(1.0, imm.quiet_a_dist_tau_s),
              1e-9);
  const auto [low, high] =
      std::minmax_element(result.disturbance_density.begin(), result.disturbance_density.end());
  std::printf("modes: w3 from %.2f to %.2f\n", *low, *high);
  EXPECT_GE(*low, imm.held_a_dist_mps3_per_sqrt_hz - 1e-9);
  EXPECT_GT(*high, q.a_dist_mps3_per_sqrt_hz);
  EXPECT_LE(*high, q.a_dist_max_mps3_per_sqrt_hz + 1e-9);
}

// A late IMU clock (the hidden clock_offset effect: the IMU's stamps 50 ms late against the
// encoders') is what the model file's calibration.imu_time_offset takes out, for the front end as
// for every estimator (io/drive_log.h ApplyCalibration). Measured: v RMSE 0.0448 -> 0.0185 m/s.
TEST(EkfRunner, TheModelFilesImuTimeOffsetTakesOutALateImuClock) {
  const DriveLog late = testing::SimulatedScenario("hidden/clock_offset");
  ModelConfig model = DefaultModelConfig(late.vehicle);
  const Evaluation before = Evaluate(late, EstimateTable(RunEkf(late, model).estimates));
  model.calibration.imu_time_offset_s = 0.05;
  DriveLog calibrated = late;
  ApplyCalibration(model, &calibrated);
  const Evaluation after = Evaluate(calibrated, EstimateTable(RunEkf(calibrated, model).estimates));
  std::printf("v RMSE %.4f -> %.4f m/s, false immobilized %ld -> %ld\n", before.velocity_rmse,
              after.velocity_rmse, static_cast<long>(before.false_immobilized_samples),
              static_cast<long>(after.false_immobilized_samples));
  EXPECT_LT(after.velocity_rmse, 0.6 * before.velocity_rmse);
  EXPECT_LT(after.velocity_rmse, 0.025);
  EXPECT_LE(after.false_immobilized_samples, before.false_immobilized_samples);
}

}  // namespace
}  // namespace slipgraph
