// End-to-end and fault-handling tests of the streaming EKF on simulated logs with known truth.
#include "solvers/ward_ekf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "evaluation/evaluation.h"
#include "io/gnss_heading_offsets.h"
#include "io/measurement_stream.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ekf_runner.h"
#include "tests/front_end_runs.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

TEST(WardEkf, Fig5HoldBackIsDetectedAndTheDisturbanceSettlesNearTheTetherForce) {
  // Ward & Iagnemma Fig. 5: 1 m/s on grass, held back with 325 N (2.78 m/s^2) for 4 s.
  const DriveLog log = testing::SimulatedScenario("fig5");
  for (bool gps : {true, false}) {
    FilterRunOptions options;
    options.use_gps = gps;
    const FilterResult result = RunEkf(log, DefaultModelConfig(log.vehicle), options);
    const Evaluation ev = Evaluate(log, EstimateTable(result.estimates));
    ASSERT_EQ(ev.events.size(), 1u);
    EXPECT_TRUE(ev.events[0].detected) << "gps=" << gps;
    EXPECT_LT(ev.events[0].delay_s, 0.4);  // the paper's mean detection time
    EXPECT_EQ(ev.false_immobilized_samples, 0);
    EXPECT_LT(ev.velocity_rmse, 0.04);  // measured 0.027 m/s
    // Settled disturbance over the last second of the hold: the target, within 10 % of
    // the tether's -2.78 m/s^2. Measured -2.88 (4 %; seeds 2-5 -2.66 to -2.84); -3.14 (13 %)
    // while weak constraint 3 balanced the tires at the a priori v_bx, 2-6 cm/s below zero,
    // where the steep rolling law near v = 0 had turned round (docs/ekf.md).
    double sum = 0.0;
    int n = 0;
    for (const WardEstimate& e : result.estimates) {
      if (e.t > 12.9 && e.t < 13.9) sum += e.x[ward::kAdist], ++n;
    }
    EXPECT_NEAR(sum / n, -2.78, 0.278) << "gps=" << gps;
  }
}

TEST(WardEkf, Ward21RunsMeetThePapersBoundsWithAndWithoutGnss) {
  // A small default version of the ward21 figure (the full suite and 100 independent ones are in
  // docs/ekf.md): seven runs of seed 1, fast and slow, with run 13's slow hold-back on mud that the
  // front end missed before the bank and the present threshold. The paper's bounds: every
  // hold-back detected, mean delay <= 0.4 s, false immobilized < 0.2 % of samples with GNSS and
  // < 0.35 % without. Measured: 7/7 both ways, delay 0.08 / 0.11 s, no false sample (at the old
  // threshold, 0.7 + 0.2, run 13 is missed without GNSS).
  const char* const names[] = {"ward21/01", "ward21/02", "ward21/03", "ward21/04",
                               "ward21/05", "ward21/06", "ward21/13"};
  std::vector<DriveLog> logs;
  for (const char* name : names) logs.push_back(testing::SimulatedScenario(name));
  for (bool gps : {true, false}) {
    std::vector<Evaluation> runs;
    for (const DriveLog& log : logs) {
      FilterRunOptions options;
      options.use_gps = gps;
      runs.push_back(Evaluate(
          log, EstimateTable(RunEkf(log, DefaultModelConfig(log.vehicle), options).estimates)));
    }
    const Evaluation total = Combine(runs, "ward21 01-06, 13");
    ASSERT_EQ(total.events.size(), 7u);
    EXPECT_EQ(total.detected(), 7) << "gps=" << gps;
    EXPECT_LE(total.mean_detection_delay_s(), 0.4) << "gps=" << gps;
    EXPECT_LT(total.false_immobilized_fraction(), gps ? 0.002 : 0.0035) << "gps=" << gps;
    EXPECT_LT(total.velocity_rmse, 0.03) << "gps=" << gps;
    std::printf("ward21 01-06, 13, gps=%d: %d/7, delay %.3f s, false %.4f %%, v RMSE %.4f\n", gps,
                total.detected(), total.mean_detection_delay_s(),
                100.0 * total.false_immobilized_fraction(), total.velocity_rmse);
  }
}

// Wheel odometry, r times the wheels' mean speed and never flagged immobilized: the trivial
// estimator the bounds below must be far from.
NumericTable WheelOdometry(const DriveLog& log) {
  NumericTable table;
  table.names = {"t", "v_bx", "immobilized"};
  const int wheels = static_cast<int>(WheelNames(log.vehicle.type).size());
  for (const WheelSample& w : log.wheels) {
    double sum = 0.0;
    for (int i = 0; i < wheels; ++i) sum += w.omega_radps[i];
    table.columns["t"].push_back(w.t);
    table.columns["v_bx"].push_back(log.vehicle.wheel_radius_m * sum / wheels);
    table.columns["immobilized"].push_back(0.0);
  }
  return table;
}

// Every run of ward21 seeds 1-4 (80 hold-backs; the bank with GNSS), against wheel odometry on
// the same logs. Bounds: every hold-back detected, mean delay <= 0.4 s, false immobilized under
// 0.2 % of samples (the paper's), velocity RMSE under half the odometry's. Odometry, the
// control, fails the detection and velocity bounds on every seed (0/20, 0.20-0.23 m/s). Known
// failures are asserted as such, so that a change that mends or worsens them says so: seed 2
// misses one hold-back (19/20). Without the wheels' check on the bias (ModelConfig::
// slip_persistence) seed 2 also flagged 0.27 % of its samples (run 19, a robot at 0.09 m/s whose
// velocity sank after a gentle hold-back) and seed 4 0.55 %. Measured: seeds 1-4 v RMSE 0.0166
// 0.0179 0.0170 0.0181 m/s, delay 0.06 0.00 0.03 0.02 s, false 0 0 0.002 0 %.
TEST(WardEkf, Ward21SeedsOneToFourAgainstWheelOdometry) {
  struct Expected {
    int detected;
    bool false_alarms_within_bound;
  };
  const Expected expected[] = {{20, true}, {19, true}, {20, true}, {20, true}};
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    std::vector<Evaluation> ekf, odometry;
    for (const sim::ScenarioRun& run : sim::ExpandScenario("ward21", seed)) {
      DriveLog log = sim::Simulate(run.scenario, run.seed).log;
      log.directory = run.scenario.name;
      ekf.push_back(
          Evaluate(log, EstimateTable(RunEkf(log, DefaultModelConfig(log.vehicle)).estimates)));
      odometry.push_back(Evaluate(log, WheelOdometry(log)));
    }
    const Evaluation e = Combine(ekf, "ekf");
    const Evaluation o = Combine(odometry, "odometry");
    const Expected& x = expected[seed - 1];
    SCOPED_TRACE("seed " + std::to_string(seed));
    ASSERT_EQ(e.events.size(), 20u);
    EXPECT_EQ(e.detected(), x.detected);
    EXPECT_LE(e.mean_detection_delay_s(), 0.4);
    EXPECT_EQ(e.false_immobilized_fraction() < 0.002, x.false_alarms_within_bound)
        << 100.0 * e.false_immobilized_fraction() << " %";
    EXPECT_LT(e.false_immobilized_fraction(), 0.015);
    EXPECT_LT(e.velocity_rmse, 0.5 * o.velocity_rmse);
    EXPECT_EQ(o.detected(), 0);
    EXPECT_GT(o.velocity_rmse, 0.15);
  }
}

TEST(WardEkf, TheStartDoesNotLeakIntoTheAccelerometerOffset) {
  // Each ward21 run rests 3 s before it drives off. The encoders read still for the first
  // hundredth of a second of the start while the body already accelerates; those samples must
  // not reach the at-rest offset EMA (ModelConfig::offset_rest_guard_s). Truth: the mean
  // accelerometer reading over the rest (flat ground, nothing moving). Measured on runs 1-6: the
  // offset 2 s into the drive is off by -0.004 to +0.004 with the guard, +0.004 to +0.013 (all
  // positive: the start's acceleration) without it.
  double sum_error = 0.0;
  for (const char* name :
       {"ward21/01", "ward21/02", "ward21/03", "ward21/04", "ward21/05", "ward21/06"}) {
    const DriveLog log = testing::SimulatedScenario(name);
    double rest_sum = 0.0;
    int n = 0;
    for (const ImuSample& s : log.imu) {
      if (s.t > 1.0 && s.t < 3.0) rest_sum += s.ax, ++n;
    }
    const FilterResult result = RunEkf(log, DefaultModelConfig(log.vehicle));
    double offset = std::nan("");
    for (const WardEstimate& e : result.estimates) {
      if (e.t <= 5.0) offset = e.accel_offset_mps2;
    }
    const double error = offset - rest_sum / n;
    EXPECT_LT(std::abs(error), 0.007) << name;  // the EMA's own noise is about 0.0035
    sum_error += error;
  }
  EXPECT_LT(std::abs(sum_error / 6.0), 0.003);  // without the guard: +0.0077
}

TEST(WardEkf, AYawOffTheCourseIsCorrectedFromTheFixes) {
  // An AHRS whose yaw reads 0.4 rad off the direction the robot drives (a heading reference the
  // model does not have): each GNSS velocity projected on that yaw reads the speed times
  // cos(0.4), 8 % slow. The front end finds the offset from the fixes' course
  // (factors/gnss_heading_offset.h) and stays as close to truth as on the log as simulated;
  // with the correction off (the control) its velocity follows the projection down. The
  // model's law is softer than the soil's (0.4 x C1), so that GNSS, not the wheels, holds the
  // velocity, as on a robot whose law is a guess. Measured, seeds 1-2: RMSE 0.0709 / 0.0698 m/s
  // as simulated, 0.0718 / 0.0704 rotated, 0.0814 / 0.0779 rotated with the correction off.
  for (uint64_t seed : {1, 2}) {
    DriveLog log = sim::Simulate(testing::FlatLagrScenario("gravel", 1.0, 60.0), seed).log;
    log.vehicle.tire.C1 *= 0.4;
    log.vehicle.law_samples.clear();
    const ModelConfig model = DefaultModelConfig(log.vehicle);
    const auto rmse = [&log](const FilterResult& result) {
      const std::vector<double> truth_v =
          testing::TruthAt(log, result.estimates, [](const TruthSample& s) { return s.vx; });
      double sum_sq = 0.0;
      for (size_t i = 0; i < truth_v.size(); ++i) {
        const double e = result.estimates[i].x[ward::kVbx] - truth_v[i];
        sum_sq += e * e;
      }
      return std::sqrt(sum_sq / truth_v.size());
    };
    const FilterResult as_simulated = RunEkf(log, model);
    EXPECT_EQ(as_simulated.stats.gnss_heading_corrected, 0) << seed;
    for (AttitudeSample& a : log.attitude) a.yaw += 0.4;
    const FilterResult corrected = RunEkf(log, model);
    ModelConfig off = model;
    off.gnss_heading_from_course = false;
    const FilterResult control = RunEkf(log, off);
    EXPECT_EQ(control.stats.gnss_heading_corrected, 0) << seed;
    EXPECT_GT(corrected.stats.gnss_heading_corrected, 0) << seed;
    EXPECT_NEAR(corrected.stats.gnss_heading_offset_rad, -0.4, 0.05) << seed;
    // One rule: the smoothers' offsets over the log (io/gnss_heading_offsets.h) are the front
    // end's, fix by fix; the last one applied is the same number.
    const std::vector<double> offsets = GnssHeadingOffsets(log, model);
    const long applied =
        std::count_if(offsets.begin(), offsets.end(), [](double offset) { return offset != 0.0; });
    EXPECT_EQ(applied, corrected.stats.gnss_heading_corrected) << seed;
    const auto last =
        std::find_if(offsets.rbegin(), offsets.rend(), [](double offset) { return offset != 0.0; });
    ASSERT_NE(last, offsets.rend());
    EXPECT_DOUBLE_EQ(*last, corrected.stats.gnss_heading_offset_rad) << seed;
    EXPECT_LT(rmse(corrected), 1.05 * rmse(as_simulated)) << seed;
    EXPECT_GT(rmse(control), 1.08 * rmse(corrected)) << seed;
  }
}

TEST(WardEkf, ALogThatStartsMovingNeedsNoRest) {
  // The robot drives off at 0.5 s (a rest of half the 1 s of IMU samples that initialise the
  // offsets) or at once; a rest start would take the plain mean of that second, which carries
  // the start's acceleration (the control below). solvers/imu_offsets.h: the short rest is used,
  // or the wheels' acceleration is subtracted. Velocity error over the first seconds, with truth
  // above 0.3 m/s, seeds 1-3: measured RMS 2.0-2.7 %, worst 5.2-7.1 % after the 0.5 s rest, RMS
  // 1.8-2.8 %, worst 7.0-10.7 % from the start (both in the ramp: the same drive after a 2 s
  // rest has its worst at 5.1 %, the filter's lag behind 0.8 m/s^2 on gravel).
  for (double rest_s : {0.5, 0.0}) {
    sim::Scenario sc = testing::FlatLagrScenario("gravel", 1.0, 20.0);
    sc.rest_start_s = rest_s;
    for (uint64_t seed : {1, 2, 3}) {
      const DriveLog log = sim::Simulate(sc, seed).log;
      const ModelConfig model = DefaultModelConfig(log.vehicle);
      const FilterResult result = RunEkf(log, model);
      EXPECT_EQ(result.stats.offset_moving_start, rest_s == 0.0);
      const std::vector<double> truth_v =
          testing::TruthAt(log, result.estimates, [](const TruthSample& s) { return s.vx; });
      double worst = 0.0, sum_sq = 0.0;
      int n = 0;
      for (size_t i = 0; i < result.estimates.size(); ++i) {
        const double t = result.estimates[i].t;
        if (t < 1.0 || t > 6.0 || truth_v[i] < 0.3) continue;
        const double relative = (result.estimates[i].x[ward::kVbx] - truth_v[i]) / truth_v[i];
        worst = std::max(worst, std::abs(relative));
        sum_sq += relative * relative, ++n;
      }
      ASSERT_GT(n, 300);
      EXPECT_LT(std::sqrt(sum_sq / n), 0.05) << rest_s << " s rest, seed " << seed;
      EXPECT_LT(worst, rest_s > 0.0 ? 0.08 : 0.12) << rest_s << " s rest, seed " << seed;

      // Control: the plain mean of the initial samples is off by the start's mean acceleration
      // (0.4 m/s^2 after the 0.5 s rest, 0.75 m/s^2 from the start).
      double sum = 0.0;
      int used = 0;
      for (const ImuSample& s : log.imu) {
        if (used < model.offset_init_samples) sum += s.ax, ++used;
      }
      EXPECT_GT(std::abs(sum / used - result.estimates.back().accel_offset_mps2), 0.2);
    }
  }
}

TEST(WardEkf, RunsWithoutGnssAndSaysSo) {
  const DriveLog log = testing::SimulatedScenario("ward21/04");
  FilterRunOptions options;
  options.use_gps = false;
  const FilterResult result = RunEkf(log, DefaultModelConfig(log.vehicle), options);
  EXPECT_EQ(result.stats.gps.used, 0);
  bool said = false;
  for (const std::string& note : result.notes) said = said || note == "no GNSS velocity used";
  EXPECT_TRUE(said);
  EXPECT_EQ(result.estimates.size(), log.wheels.size());
}

TEST(WardEkf, AnEffectWithoutAnEstimatorTermIsSaidNotSilentlyIgnored) {
  const DriveLog log = testing::SimulatedScenario("fig5");
  ModelConfig model = DefaultModelConfig(log.vehicle);
  model.effects = {"quadratic_drag"};
  const FilterResult result = RunEkf(log, model);
  bool said = false;
  for (const std::string& note : result.notes) {
    said = said || note.find("'quadratic_drag'") != std::string::npos;
  }
  EXPECT_TRUE(said);
}

TEST(WardEkf, ANanComponentIsDroppedAlone) {
  const DriveLog log = testing::SimulatedScenario("fig5");
  WardEkf ekf(log.vehicle, DefaultModelConfig(log.vehicle));
  for (size_t i = 0; i < 400; ++i) {
    ImuSample imu = log.imu[i];
    if (i == 350) imu.gz = std::nan("");
    ekf.AddImu(imu);
    const SideSpeeds s = DrivenSideSpeeds(log.wheels[i], log.vehicle.type);
    ekf.AddWheels(log.wheels[i].t, s.left_radps, i == 360 ? std::nan("") : s.right_radps);
  }
  EXPECT_EQ(ekf.stats().imu.dropped_components, 1);
  EXPECT_EQ(ekf.stats().wheels.dropped_components, 1);
  EXPECT_EQ(ekf.stats().imu.used, 400 - 100);  // after the 100 offset-initialisation samples
  const WardEstimate e = ekf.Estimate();
  for (double v : e.x) EXPECT_TRUE(std::isfinite(v));
}

TEST(WardEkf, InconsistentGnssIsGatedThenReadmittedAndCounted) {
  // Driving at 1 m/s; the receiver reports 3 m/s. The first fix is rejected, the next one is
  // re-admitted rather than silently rejecting every fix.
  const DriveLog log = testing::SimulatedScenario("fig5");
  WardEkf ekf(log.vehicle, DefaultModelConfig(log.vehicle));
  int gps_seen = 0;
  for (const StreamEntry& e : MergeStreams(log)) {
    if (e.t > 9.5) break;
    if (e.stream == Stream::kImu) ekf.AddImu(log.imu[e.index]);
    if (e.stream == Stream::kAttitude) ekf.AddAttitude(log.attitude[e.index]);
    if (e.stream == Stream::kWheels) {
      const SideSpeeds s = DrivenSideSpeeds(log.wheels[e.index], log.vehicle.type);
      ekf.AddWheels(log.wheels[e.index].t, s.left_radps, s.right_radps);
    }
    if (e.stream == Stream::kGps && e.t > 7.5) {
      GpsSample bad = log.gps[e.index];
      bad.vx *= 3.0, bad.vy *= 3.0;
      ekf.AddGps(bad);
      ++gps_seen;
    }
  }
  ASSERT_EQ(gps_seen, 2);
  EXPECT_EQ(ekf.stats().gps.rejected, 1);
  EXPECT_EQ(ekf.stats().gps.forced, 1);
}

TEST(WardEkf, MissingEncoderDataIsNeverReportedAsImmobilization) {
  const DriveLog log = testing::SimulatedScenario("fig5");
  WardEkf ekf(log.vehicle, DefaultModelConfig(log.vehicle));
  bool flagged = false;
  // The encoders fall silent 0.5 s into the hold-back, once the robot is flagged (no GNSS).
  testing::FeedStreams(
      log, &ekf,
      [](const StreamEntry& e) {
        return e.stream != Stream::kGps && (e.stream != Stream::kWheels || e.t < 11.0);
      },
      [&](const StreamEntry&) { flagged = flagged || ekf.Estimate().slip.immobilized; });
  EXPECT_TRUE(flagged);  // it was flagged while the encoders spoke
  EXPECT_FALSE(ekf.Estimate().slip.immobilized);
}

TEST(WardEkf, SumsTheLogLikelihoodOnlyWhenAsked) {
  const DriveLog log = testing::SimulatedScenario("fig5");
  EkfOptions tracked;
  tracked.track_log_likelihood = true;
  WardEkf plain(log.vehicle, DefaultModelConfig(log.vehicle));
  WardEkf weighing(log.vehicle, DefaultModelConfig(log.vehicle), tracked);
  for (WardEkf* ekf : {&plain, &weighing}) {
    testing::FeedStreams(
        log, ekf, [](const StreamEntry& e) { return e.t <= 5.0 && e.stream != Stream::kWheels; });
  }
  EXPECT_EQ(plain.TakeLogLikelihood(), 0.0);
  const double l = weighing.TakeLogLikelihood();
  EXPECT_TRUE(std::isfinite(l));
  EXPECT_NE(l, 0.0);
  EXPECT_EQ(weighing.TakeLogLikelihood(), 0.0);  // reset by the call
}

TEST(WardEkf, ScoresOneGnssFixWithoutTrackingTheRest) {
  // AddGpsScored returns the fix's log-likelihood, the same value a tracked filter sums for it,
  // and leaves an untracked filter's sum at zero (the bank takes no logarithm elsewhere).
  const DriveLog log = testing::SimulatedScenario("fig5");
  EkfOptions tracked_options;
  tracked_options.track_log_likelihood = true;
  WardEkf plain(log.vehicle, DefaultModelConfig(log.vehicle));
  WardEkf tracked(log.vehicle, DefaultModelConfig(log.vehicle), tracked_options);
  // Per fix: the score, and what TakeLogLikelihood then returns. Each score is also checked
  // against log N(nu; 0, P_vv + r) by hand from the filter's estimate before the fix: nu the fix's
  // velocity along body x (at the last attitude fed) minus v_bx.
  int checked = 0;
  const auto score_fixes = [&](WardEkf* ekf) {
    std::vector<std::pair<double, double>> fixes;
    const AttitudeSample* attitude = nullptr;
    testing::FeedStreams(log, ekf, [&](const StreamEntry& e) {
      if (e.t > 6.0) return false;
      if (e.stream == Stream::kAttitude) attitude = &log.attitude[e.index];
      if (e.stream != Stream::kGps) return true;
      ekf->TakeLogLikelihood();  // the other streams' share so far
      const GpsSample& g = log.gps[e.index];
      const WardEstimate before = ekf->Estimate();
      const double scored = ekf->AddGpsScored(g);
      fixes.emplace_back(scored, ekf->TakeLogLikelihood());
      if (attitude != nullptr && before.sd[ward::kVbx] > 0.0) {
        const double cp = std::cos(attitude->pitch);
        const double along = g.vx * std::cos(attitude->yaw) * cp +
                             g.vy * std::sin(attitude->yaw) * cp - g.vz * std::sin(attitude->pitch);
        const double nu = along - before.x[ward::kVbx];
        const double r =
            GnssVelocitySd(g, DefaultModelConfig(log.vehicle).measurement.gps_sd_v_mps);
        const double s = before.sd[ward::kVbx] * before.sd[ward::kVbx] + r * r;
        EXPECT_NEAR(scored, -0.5 * (nu * nu / s + std::log(2.0 * M_PI * s)), 1e-9) << g.t;
        ++checked;
      }
      return false;  // fed here
    });
    return fixes;
  };
  const auto untracked = score_fixes(&plain), summed = score_fixes(&tracked);
  EXPECT_GE(checked, 8);
  ASSERT_GE(untracked.size(), 5u);
  ASSERT_EQ(untracked.size(), summed.size());
  for (size_t i = 0; i < untracked.size(); ++i) {
    EXPECT_TRUE(std::isfinite(untracked[i].first));
    EXPECT_EQ(untracked[i].first, summed[i].first);
    EXPECT_EQ(summed[i].second, summed[i].first);  // tracked: the fix also in the sum
    EXPECT_EQ(untracked[i].second, 0.0);           // untracked: nothing summed
  }
}

TEST(WardEkf, OptionsAreValidated) {
  EkfOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.initial_sd[2] = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  options = EkfOptions();
  options.gnss_fading_fixes = 0.5;  // an EMA over less than one fix
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("gnss_fading"), std::string::npos);
}

// The matched control of a front-end feature, on three ward21 runs of seed 1 without it (a) and
// with it (b): the same detections and false alarms, the velocity error within rmse_ratio.
void ExpectMatchedControlUnchanged(const Evaluation& a, const Evaluation& b, double rmse_ratio) {
  std::printf(
      "ward21 seed 1, runs 01-03: detected %d -> %d, false %ld -> %ld, v RMSE %.4f -> %.4f\n",
      a.detected(), b.detected(), a.false_immobilized_samples, b.false_immobilized_samples,
      a.velocity_rmse, b.velocity_rmse);
  EXPECT_EQ(b.detected(), a.detected());
  EXPECT_EQ(b.false_immobilized_samples, a.false_immobilized_samples);
  EXPECT_LT(b.velocity_rmse, rmse_ratio * a.velocity_rmse);
}

// Fading memory on GNSS (EkfOptions::gnss_fading_*) on three ward21m runs of seed 2 whose
// velocity drifts off while the wheels and GNSS agree (a peaked tire law and a slowly wrong
// AHRS the model lacks; docs/mismatch.md), with the paper's accelerometer bias walk. Measured:
// false immobilized 44.4 % of samples without it, 13.6 % with it, velocity RMSE 0.155 -> 0.062
// m/s. The control: on three matched
// ward21 runs, the paper's single filter (a bank does not fade), it changes neither the
// detections nor, beyond 5 %, the velocity error.
TEST(WardEkf, GnssFadingPullsADriftingVelocityBackAndLeavesAConsistentFilterAlone) {
  const auto suite = [](const std::vector<const char*>& names, uint64_t seed, bool fading) {
    FilterRunOptions options;
    options.multiple_model = false;
    options.ekf.gnss_fading_fixes = fading ? kGnssFadingFixes : 0.0;
    return testing::EvaluateFrontEnd(names, seed, options, UsePapersAccelBias);
  };
  const std::vector<const char*> drifting = {"ward21m/06", "ward21m/10", "ward21m/21"};
  const Evaluation without = suite(drifting, 2, false), with = suite(drifting, 2, true);
  std::printf("ward21m seed 2, runs 06 10 21: false %.3f -> %.3f, v RMSE %.4f -> %.4f\n",
              without.false_immobilized_fraction(), with.false_immobilized_fraction(),
              without.velocity_rmse, with.velocity_rmse);
  EXPECT_GT(without.false_immobilized_fraction(), 0.2);
  EXPECT_LT(with.false_immobilized_fraction(), 0.5 * without.false_immobilized_fraction());
  EXPECT_LT(with.velocity_rmse, 0.7 * without.velocity_rmse);
  const std::vector<const char*> matched = {"ward21/01", "ward21/02", "ward21/03"};
  const Evaluation a = suite(matched, 1, false), b = suite(matched, 1, true);
  ExpectMatchedControlUnchanged(a, b, 1.05);
}

// Weak constraint 4 on the wheels' speeds smoothed over 0.1 s (weak_constraints.still_smoothing) on
// a ward21m run of seed 20 without GNSS whose robot stalls for 4 s, wheels and body held: its
// encoders read one count now and then while the wheels stand. Taken reading by reading, each
// such count restarts the at-rest timer, the constraint never holds the disturbance and the bias
// at zero, and the velocity sinks to -0.19 m/s against the held disturbance through the tire
// law's braking branch; after the stall the filter stays behind the robot, flagged immobilized
// (docs/mismatch.md). Measured: false immobilized 6.8 -> 0.8 % of samples, velocity RMSE 0.101 ->
// 0.023 m/s. The control: three matched ward21 runs, the single filter on the mean law: the
// detections and the false alarms unchanged, the velocity error within 5 %.
TEST(WardEkf, AStandingEncodersOddCountDoesNotKeepTheFilterFromRest) {
  const auto suite = [](const std::vector<const char*>& names, uint64_t seed, bool smoothed,
                        bool use_gps) {
    FilterRunOptions options;
    options.multiple_model = false;
    options.use_gps = use_gps;
    return testing::EvaluateFrontEnd(names, seed, options, [smoothed](ModelConfig* model) {
      model->weak_constraints.still_smoothing_s = smoothed ? 0.1 : 0.0;
    });
  };
  const Evaluation each = suite({"ward21m/03"}, 20, false, false),
                   smoothed = suite({"ward21m/03"}, 20, true, false);
  std::printf("ward21m seed 20, run 03, no GNSS: false %.4f -> %.4f, v RMSE %.4f -> %.4f\n",
              each.false_immobilized_fraction(), smoothed.false_immobilized_fraction(),
              each.velocity_rmse, smoothed.velocity_rmse);
  EXPECT_GT(each.false_immobilized_fraction(), 0.04);
  EXPECT_LT(smoothed.false_immobilized_fraction(), 0.2 * each.false_immobilized_fraction());
  EXPECT_LT(smoothed.velocity_rmse, 0.4 * each.velocity_rmse);
  const std::vector<const char*> matched = {"ward21/01", "ward21/02", "ward21/03"};
  const Evaluation a = suite(matched, 1, false, true), b = suite(matched, 1, true, true);
  ExpectMatchedControlUnchanged(a, b, 1.05);
}

// Weak constraint 1 doubted as the push grows (weak_constraints.oppose_motion_cauchy_scale) on
// three ward21m runs of seed 4 whose robot surges when a hold-back lets go: the peaked law's tread,
// relaxing, pushes on while the body overtakes its wheels, a force eq. (8) cannot give. The
// paper's constraint holds that push at zero through the law's slope, the velocity leaves the
// surge 0.1-0.15 m/s below the body's and the held disturbance then stands the robot still for
// seconds (docs/mismatch.md). Measured: false immobilized 9.97 -> 0.24 % of samples, velocity
// RMSE 0.098 -> 0.034 m/s. The control: three matched ward21 runs, the single filter on the mean
// law: the detections and the false alarms unchanged, the velocity error 0.0166 -> 0.0173 m/s
// (+4 %; +2-3 % over seeds 11-40's 600 runs, hence the bound of 6 %).
TEST(WardEkf, DoubtedOpposeMotionLetsTheVelocityFollowASurge) {
  const auto suite = [](const std::vector<const char*>& names, uint64_t seed, double scale) {
    FilterRunOptions options;
    options.multiple_model = false;
    return testing::EvaluateFrontEnd(names, seed, options, [scale](ModelConfig* model) {
      model->weak_constraints.oppose_motion_cauchy_scale_mps2 = scale;
      UsePapersAccelBias(model);
    });
  };
  const double kDefault = WeakConstraintConfig().oppose_motion_cauchy_scale_mps2;
  const std::vector<const char*> surging = {"ward21m/09", "ward21m/14", "ward21m/18"};
  const Evaluation paper = suite(surging, 4, 0.0), doubted = suite(surging, 4, kDefault);
  std::printf("ward21m seed 4, runs 09 14 18: false %.4f -> %.4f, v RMSE %.4f -> %.4f\n",
              paper.false_immobilized_fraction(), doubted.false_immobilized_fraction(),
              paper.velocity_rmse, doubted.velocity_rmse);
  EXPECT_EQ(doubted.detected(), paper.detected());
  EXPECT_GT(paper.false_immobilized_fraction(), 0.05);
  EXPECT_LT(doubted.false_immobilized_fraction(), 0.2 * paper.false_immobilized_fraction());
  EXPECT_LT(doubted.velocity_rmse, 0.5 * paper.velocity_rmse);
  const std::vector<const char*> matched = {"ward21/01", "ward21/02", "ward21/03"};
  const Evaluation a = suite(matched, 1, 0.0), b = suite(matched, 1, kDefault);
  ExpectMatchedControlUnchanged(a, b, 1.06);
}

// The attitude's slow error in the front end's accelerometer bias walk
// (ProcessNoiseConfig::attitude_error_walk_s) on the three ward21m runs of seed 2 whose velocity
// drifts off (their AHRS is off by up to 0.3 deg for tens of seconds, 0.05 m/s^2 of gravity the
// paper's bias walk of 0.02 m/s^2 over 300 s cannot follow; docs/mismatch.md). The default
// front end, with and without GNSS. Measured: false immobilized 13.6 -> 0.0 % of samples with
// GNSS, 46.1 -> 15.2 % without; velocity RMSE 0.062 -> 0.025 and 0.166 -> 0.073 m/s. The control:
// three matched ward21 runs (the bank, an AHRS of 0.002 rad stated and white): the same
// detections and false alarms, the velocity error within 5 % (0.0159 -> 0.0164 m/s).
TEST(WardEkf, TheAttitudesSlowErrorLetsTheBiasFollowAWrongAhrs) {
  const auto suite = [](const std::vector<const char*>& names, uint64_t seed, bool gnss,
                        bool slow_error) {
    FilterRunOptions options;
    options.use_gps = gnss;
    return testing::EvaluateFrontEnd(names, seed, options, [slow_error](ModelConfig* model) {
      const double walk_s = model->process.attitude_error_walk_s;
      UsePapersAccelBias(model);  // the wheels' check off in both
      if (slow_error) model->process.attitude_error_walk_s = walk_s;
    });
  };
  const std::vector<const char*> drifting = {"ward21m/06", "ward21m/10", "ward21m/21"};
  for (const bool gnss : {true, false}) {
    const Evaluation paper = suite(drifting, 2, gnss, false);
    const Evaluation slow = suite(drifting, 2, gnss, true);
    std::printf("ward21m seed 2, runs 06 10 21, %s: false %.4f -> %.4f, v RMSE %.4f -> %.4f\n",
                gnss ? "GNSS" : "no GNSS", paper.false_immobilized_fraction(),
                slow.false_immobilized_fraction(), paper.velocity_rmse, slow.velocity_rmse);
    EXPECT_EQ(slow.detected(), paper.detected());
    EXPECT_GT(paper.false_immobilized_fraction(), 0.1);
    EXPECT_LT(slow.false_immobilized_fraction(), 0.5 * paper.false_immobilized_fraction());
    EXPECT_LT(slow.velocity_rmse, 0.6 * paper.velocity_rmse);
  }
  const std::vector<const char*> matched = {"ward21/01", "ward21/02", "ward21/03"};
  const Evaluation a = suite(matched, 1, true, false), b = suite(matched, 1, true, true);
  ExpectMatchedControlUnchanged(a, b, 1.05);
}

// The wheels' check tests' own runs, `suite(names, seed, gnss, on)`: two ward21m robots whose
// wheels stall with the held body and then spin up (seed 8 run 07, seed 5 run 10), where the slip
// rises on its own, are detected with it on; on three matched ward21 runs (the bank) it changes
// neither the detections nor the false alarms, nor the velocity error beyond rmse_ratio.
template <typename Suite>
void ExpectTheStallsDetected(const Suite& suite, bool gnss) {
  EXPECT_EQ(suite({"ward21m/07"}, 8, gnss, true).detected(), 1)
      << "seed 8 run 07, " << (gnss ? "GNSS" : "no GNSS");
  EXPECT_EQ(suite({"ward21m/10"}, 5, gnss, true).detected(), 1)
      << "seed 5 run 10, " << (gnss ? "GNSS" : "no GNSS");
}

template <typename Suite>
void ExpectMatchedControlUnchanged(const Suite& suite, double rmse_ratio) {
  const std::vector<const char*> matched = {"ward21/01", "ward21/02", "ward21/03"};
  ExpectMatchedControlUnchanged(suite(matched, 1, true, false), suite(matched, 1, true, true),
                                rmse_ratio);
}

// The wheels' check on the accelerometer bias (ModelConfig::slip_persistence) on slow ward21m
// robots (0.11-0.15 m/s) whose velocity an attitude error drives down while their wheels hold
// their speed, until the slip reads as an immobilization (seed 8 runs 10 and 13, seed 2 run 03;
// docs/mismatch.md), with and without GNSS, the attitude's walk in the bias either way; and on two
// whose wheels stall with the held body and then spin up (seed 8 run 07, seed 5 run 10), where
// the slip rises on its own and the check must not hold the velocity to the wheels. Measured on
// the drifting runs: false immobilized 11.5 -> 0.73 % of samples with GNSS, 29.8 -> 0.85 % without;
// velocity RMSE 0.047 -> 0.021 and 0.067 -> 0.025 m/s; the stalls detected either way. The
// control: three matched ward21 runs (the bank): the same detections and false alarms, velocity
// error 0.0164 -> 0.0153 m/s.
TEST(WardEkf, TheWheelsCheckHoldsTheBiasOfASlowRobot) {
  const auto suite = [](const std::vector<const char*>& names, uint64_t seed, bool gnss,
                        bool check) {
    FilterRunOptions options;
    options.use_gps = gnss;
    return testing::EvaluateFrontEnd(names, seed, options, [check](ModelConfig* model) {
      if (!check) model->slip_persistence.interval_s = 0.0;
    });
  };
  for (const bool gnss : {true, false}) {
    Evaluation without[2], with[2];
    const std::pair<std::vector<const char*>, uint64_t> drifting[] = {
        {{"ward21m/10", "ward21m/13"}, 8}, {{"ward21m/03"}, 2}};
    for (int i = 0; i < 2; ++i) {
      without[i] = suite(drifting[i].first, drifting[i].second, gnss, false);
      with[i] = suite(drifting[i].first, drifting[i].second, gnss, true);
    }
    const Evaluation a = Combine({without[0], without[1]}, "without"),
                     b = Combine({with[0], with[1]}, "with");
    std::printf(
        "ward21m drifting, %s: false %.4f -> %.4f, v RMSE %.4f -> %.4f, detected %d -> %d\n",
        gnss ? "GNSS" : "no GNSS", a.false_immobilized_fraction(), b.false_immobilized_fraction(),
        a.velocity_rmse, b.velocity_rmse, a.detected(), b.detected());
    EXPECT_EQ(b.detected(), a.detected());
    EXPECT_GT(a.false_immobilized_fraction(), 0.05);
    EXPECT_LT(b.false_immobilized_fraction(), 0.25 * a.false_immobilized_fraction());
    EXPECT_LT(b.velocity_rmse, 0.7 * a.velocity_rmse);
    ExpectTheStallsDetected(suite, gnss);
  }
  ExpectMatchedControlUnchanged(suite, 1.05);
}

// The wheels' check applies a bias error that lasts past its gate, with the velocity it moved
// (SlipPersistenceConfig::lasting_intervals), on slow ward21m robots whose bias estimate a
// hold-back's release left wrong by 0.06-0.09 m/s^2: the velocity then sinks off the wheels for
// seconds, every interval beyond the gate, and without GNSS the slip it reaches is held as an
// immobilization for the rest of the run (seed 14 run 02, seed 2 run 03). Measured without GNSS:
// false immobilized 32 -> 0.17 % of samples, velocity RMSE 0.083 -> 0.033 m/s (with GNSS 8.1 % ->
// 0, 0.051 -> 0.026 m/s). A robot that speeds up after its hold-back (seed 14 run 15: 0.3-0.5 m/s^2
// for seconds) is a force, not a bias: left out as before. The stalls stay detected; the matched
// control does not move.
TEST(WardEkf, TheWheelsCheckAppliesABiasErrorThatLasts) {
  const auto suite = [](const std::vector<const char*>& names, uint64_t seed, bool gnss,
                        bool lasting) {
    FilterRunOptions options;
    options.use_gps = gnss;
    return testing::EvaluateFrontEnd(names, seed, options, [lasting](ModelConfig* model) {
      if (!lasting) model->slip_persistence.lasting_intervals = 0;
    });
  };
  for (const bool gnss : {true, false}) {
    const Evaluation a = Combine({suite({"ward21m/02"}, 14, gnss, false),
                                  suite({"ward21m/03"}, 2, gnss, false)},
                                 "without"),
                     b = Combine({suite({"ward21m/02"}, 14, gnss, true),
                                  suite({"ward21m/03"}, 2, gnss, true)},
                                 "with");
    const Evaluation speeding_a = suite({"ward21m/15"}, 14, gnss, false),
                     speeding_b = suite({"ward21m/15"}, 14, gnss, true);
    std::printf(
        "%s: false %.4f -> %.4f, v RMSE %.4f -> %.4f, detected %d -> %d; speeding up after its "
        "hold-back: v RMSE %.4f -> %.4f\n",
        gnss ? "GNSS" : "no GNSS", a.false_immobilized_fraction(), b.false_immobilized_fraction(),
        a.velocity_rmse, b.velocity_rmse, a.detected(), b.detected(), speeding_a.velocity_rmse,
        speeding_b.velocity_rmse);
    EXPECT_GT(a.false_immobilized_fraction(), 0.05);
    EXPECT_LT(b.false_immobilized_fraction(), 0.1 * a.false_immobilized_fraction());
    EXPECT_LT(b.velocity_rmse, 0.7 * a.velocity_rmse);
    EXPECT_NEAR(speeding_b.velocity_rmse, speeding_a.velocity_rmse,
                0.05 * speeding_a.velocity_rmse);
    if (!gnss) {
      EXPECT_GT(a.false_immobilized_fraction(), 0.2);
      EXPECT_LT(b.velocity_rmse, 0.5 * a.velocity_rmse);
    }
    ExpectTheStallsDetected(suite, gnss);
  }
  ExpectMatchedControlUnchanged(suite, 1.0001);
}

// The checks the filter applied are kept for the smoothers (EkfStats::wheel_bias_checks) as the
// whole bias c_ax + b_ax: an accelerometer that reads 0.05 m/s^2 more from the middle of a
// hidden/none drive on is read 0.05 m/s^2 higher by the checks from some seconds later on, and the
// same before it. One per check applied, in time order.
TEST(WardEkf, TheChecksKeptForTheSmoothersReadTheWholeBias) {
  const DriveLog log = testing::SimulatedScenario("hidden/none");
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  DriveLog shifted = log;
  const double t_shift = 0.5 * (log.imu.front().t + log.imu.back().t);
  for (ImuSample& imu : shifted.imu) {
    if (imu.t >= t_shift) imu.ax += 0.05;
  }
  const FilterResult plain = RunEkf(log, model), moved = RunEkf(shifted, model);
  const auto mean_bias = [](const FilterResult& run, double from, double to, int* count) {
    double sum = 0.0;
    *count = 0;
    for (const AccelBiasMeasurement& m : run.stats.wheel_bias_checks) {
      if (m.t < from || m.t > to) continue;
      sum += m.bias_mps2;
      ++*count;
    }
    return *count > 0 ? sum / *count : std::nan("");
  };
  for (const FilterResult* run : {&plain, &moved}) {
    const auto& checks = run->stats.wheel_bias_checks;
    EXPECT_EQ(static_cast<long>(checks.size()), run->stats.slip_persistence.used);
    for (size_t i = 1; i < checks.size(); ++i) EXPECT_GT(checks[i].t, checks[i - 1].t);
  }
  int n_before = 0, n_plain = 0, n_moved = 0, n_unused = 0;
  const double before =
      mean_bias(moved, 0.0, t_shift, &n_before) - mean_bias(plain, 0.0, t_shift, &n_unused);
  const double after = mean_bias(moved, t_shift + 5.0, log.imu.back().t, &n_moved) -
                       mean_bias(plain, t_shift + 5.0, log.imu.back().t, &n_plain);
  std::printf("checks' bias, shifted less plain: %.4f before (%d), %.4f after (%d) m/s^2\n", before,
              n_before, after, n_moved);
  ASSERT_GE(n_moved, 10);
  EXPECT_NEAR(before, 0.0, 1e-9);
  EXPECT_NEAR(after, 0.05, 0.01);
}

}  // namespace
}  // namespace slipgraph
