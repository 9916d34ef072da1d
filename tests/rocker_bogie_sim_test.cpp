#include "sim/rocker_bogie_sim.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace slipgraph
