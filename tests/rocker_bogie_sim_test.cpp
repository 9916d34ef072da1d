#include "sim/rocker_bogie_sim.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/scenarios.h"

namespace slipgraph {
namespace {

// A noise-free Wilcox run: constant slip, constant sinkage, exact sensors.
sim::Scenario QuietRun(double roughness_m) {
  sim::Scenario sc = sim::ExpandScenario("wilcox/1", 1).at(0).scenario;
  sc.rocker.roughness_rms_m = roughness_m;
  sc.rocker.slip_sd = 0.0;
  sc.rocker.articulation_sd_m = 0.0;
  sc.rocker.range_sd_m = 0.0;
  sc.rocker.soft_sinkage_m = 0.0;
  return sc;
}

// Rear-wheel position at time t from the truth rows (10 Hz, cycles at whole seconds).
double RearX(const DriveLog& log, double t) {
  for (const TruthSample& s : log.truth) {
    if (std::abs(s.t - t) < 1e-9) return s.x;
  }
  ADD_FAILURE() << "no truth at t=" << t;
  return 0.0;
}

TEST(RockerBogieSim, TerrainProfileHasTheRequestedRoughnessAndWavelengths) {
  const sim::TerrainProfile p = sim::MakeTerrainProfile(0.02, 20.0, 42);
  ASSERT_EQ(p.wavelength_m.size(), 20u);
  EXPECT_DOUBLE_EQ(p.wavelength_m.back(), 1.9);
  EXPECT_NEAR(p.wavelength_m[1] / p.wavelength_m[0], 1.3, 1e-12);
  EXPECT_NEAR(p.wavelength_m.front(), 1.9 / std::pow(1.3, 19), 1e-12);  // 1.3 cm
  double sum = 0.0, sum_sq = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double y = p.Elevation(20.0 * i / n);
    sum += y, sum_sq += y * y;
  }
  EXPECT_NEAR(std::sqrt(sum_sq / n - (sum / n) * (sum / n)), 0.02, 1e-4);
  // The contact patch attenuates short wavelengths only.
  EXPECT_LT(std::abs(p.WheelElevation(3.0, 0.02) - p.Elevation(3.0)), 0.02);
}

TEST(RockerBogieSim, ArticulationIsTheElevationDifferenceAlongTheRuts) {
  const sim::Scenario sc = QuietRun(0.02);
  const sim::SimResult r = sim::SimulateRockerBogie(sc, 3);
  const double a = sc.vehicle.axle_spacing_m, patch = sc.vehicle.wheel_radius_m / 3.0;
  const sim::TerrainProfile& left = r.profiles.at(0);
  int checked = 0;
  for (const ArticulationSample& s : r.log.articulation) {
    if (s.side != Side::kLeft) continue;
    const double x = RearX(r.log, s.t);
    // Constant sinkage cancels in the differences.
    EXPECT_NEAR(s.dz_mid, left.WheelElevation(x + a, patch) - left.WheelElevation(x, patch), 1e-12);
    EXPECT_NEAR(s.dz_front, left.WheelElevation(x + 2 * a, patch) - left.WheelElevation(x, patch),
                1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(RockerBogieSim, RangeSeesTheUnsunkTerrainAheadRelativeToTheSunkRearWheel) {
  const sim::Scenario sc = QuietRun(0.01);
  const sim::SimResult r = sim::SimulateRockerBogie(sc, 4);
  const double patch = sc.vehicle.wheel_radius_m / 3.0, sink = sc.rocker.base_sinkage_m;
  const sim::TerrainProfile& right = r.profiles.at(1);
  int checked = 0;
  for (const RangeSample& s : r.log.range) {
    if (s.side != Side::kRight || s.t != 50.0) continue;
    const double x = RearX(r.log, s.t);
    EXPECT_NEAR(s.dz, right.Elevation(x + s.d) - (right.WheelElevation(x, patch) - sink), 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, sc.rocker.range_points);
}

TEST(RockerBogieSim, AdvanceIsRimMotionTimesOneMinusSlip) {
  const sim::Scenario sc = QuietRun(0.01);
  const sim::SimResult r = sim::SimulateRockerBogie(sc, 5);
  // Between t = 20 s and 80 s the rim moves at 6.25 cm/s; the rover at 80 % of that.
  EXPECT_NEAR(RearX(r.log, 80.0) - RearX(r.log, 20.0), 60.0 * 0.0625 * 0.8, 1e-9);
  EXPECT_NEAR(r.log.truth[500].slip[0], 0.2, 1e-9);
}

TEST(RockerBogieSim, SoftPatchesSinkAndTheLeftSideCanSinkMore) {
  sim::Scenario sc = sim::ExpandScenario("wilcox/2", 1).at(0).scenario;
  sc.rocker.left_extra_sinkage_m = 0.01;
  const sim::SimResult r = sim::SimulateRockerBogie(sc, 6);
  double max_right = 0.0, max_left = 0.0, min_right = 1.0;
  for (const TruthSample& s : r.log.truth) {
    max_left = std::max(max_left, s.sinkage[0]);    // fl
    max_right = std::max(max_right, s.sinkage[3]);  // fr
    min_right = std::min(min_right, s.sinkage[3]);
  }
  EXPECT_NEAR(min_right, sc.rocker.base_sinkage_m, 1e-9);
  EXPECT_NEAR(max_right, sc.rocker.base_sinkage_m + sc.rocker.soft_sinkage_m, 1e-4);
  EXPECT_NEAR(max_left - max_right, 0.01, 1e-4);
}

// The mismatch suite (docs/mismatch.md): the slip's variation correlated over distance around
// a mean that is not 0.2, the following wheels in a deeper rut, every value in its range.
TEST(RockerBogieSim, WilcoxmSlipIsCorrelatedAndTheFollowingWheelsSinkDeeper) {
  const std::vector<sim::ScenarioRun> runs = sim::ExpandScenario("wilcoxm", 1);
  const std::vector<sim::ScenarioRun> matched = sim::ExpandScenario("wilcox", 1);
  ASSERT_EQ(runs.size(), matched.size());
  for (size_t i = 0; i < runs.size(); ++i) {
    const sim::RockerSpec& r = runs[i].scenario.rocker;
    EXPECT_EQ(runs[i].relative_directory, matched[i].relative_directory);
    EXPECT_EQ(r.roughness_rms_m, matched[i].scenario.rocker.roughness_rms_m);
    EXPECT_GE(r.slip_mean, 0.15);
    EXPECT_LE(r.slip_mean, 0.30);
    EXPECT_GE(r.slip_correlation_m, 0.2);
    EXPECT_LE(r.slip_correlation_m, 1.0);
    EXPECT_GE(r.rear_extra_sinkage, r.middle_extra_sinkage);
    EXPECT_LE(r.rear_extra_sinkage, 0.6);
    EXPECT_GE(r.contact_divisor, 2.0);
    EXPECT_LE(r.contact_divisor, 5.0);
    EXPECT_LE(std::abs(r.range_pitch_error_rad), 0.3 * M_PI / 180.0);
  }
  // One run: consecutive cycles' slips are alike (the matched suite's are independent draws),
  // and the rear wheel's sinkage where the front wheel was one axle pair earlier is deeper.
  // The soft patches' extra slip is correlated too: off for this comparison, which differs in
  // the correlation alone.
  const sim::ScenarioRun& run = runs[10];
  const sim::SimResult sim = sim::SimulateRockerBogie(run.scenario, run.seed);
  sim::Scenario correlated = run.scenario;
  correlated.rocker.soft_extra_slip = 0.0;
  sim::Scenario independent_spec = correlated;
  independent_spec.rocker.slip_correlation_m = 0.0;
  const sim::SimResult correlated_run = sim::SimulateRockerBogie(correlated, run.seed);
  const sim::SimResult independent = sim::SimulateRockerBogie(independent_spec, run.seed);
  const auto lag_one_correlation = [](const DriveLog& log) {
    std::vector<double> slips;  // one per 1 Hz cycle (truth at 10 Hz), after the start's ramp
    for (size_t k = 0; k < log.truth.size(); k += 10) {
      if (log.truth[k].t >= 10.0) slips.push_back(log.truth[k].slip[0]);
    }
    double mean = 0.0;
    for (double x : slips) mean += x / slips.size();
    double num = 0.0, den = 0.0;
    for (size_t k = 0; k + 1 < slips.size(); ++k) {
      num += (slips[k] - mean) * (slips[k + 1] - mean);
      den += (slips[k] - mean) * (slips[k] - mean);
    }
    return num / den;
  };
  EXPECT_GT(lag_one_correlation(correlated_run.log), 0.5);
  EXPECT_LT(std::abs(lag_one_correlation(independent.log)), 0.3);
  // Wheel order fl, ml, rl: off the soft patches every wheel sits at the base sinkage, the
  // middle and rear wheels deeper by their shares.
  const sim::RockerSpec& r = run.scenario.rocker;
  double front = 1.0, middle = 1.0, rear = 1.0;
  for (const TruthSample& s : sim.log.truth) {
    front = std::min(front, s.sinkage[0]);
    middle = std::min(middle, s.sinkage[1]);
    rear = std::min(rear, s.sinkage[2]);
  }
  EXPECT_NEAR(front, r.base_sinkage_m, 1e-12);
  EXPECT_NEAR(middle, r.base_sinkage_m * (1.0 + r.middle_extra_sinkage), 1e-12);
  EXPECT_NEAR(rear, r.base_sinkage_m * (1.0 + r.rear_extra_sinkage), 1e-12);
  EXPECT_GT(r.rear_extra_sinkage, 0.0);
}

}  // namespace
}  // namespace slipgraph
