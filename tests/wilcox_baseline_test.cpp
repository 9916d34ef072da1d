// Wilcox's baseline on a hand-made profile (noise-free, point contact): it recovers the advance
// per cycle and the sinkage; the left/right check catches a side that sinks more; and a small
// Monte Carlo on simulated wilcox runs (the full figures: docs/wilcox.md).
#include "solvers/wilcox_baseline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/scenarios.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace {

double Terrain(double x) {
  return 0.01 * std::sin(2.0 * M_PI * x / 0.3) + 0.005 * std::sin(2.0 * M_PI * x / 0.11 + 1.0);
}

// 40 cycles of 5 cm advance (rim 6.25 cm: 20 % slip); sinkage per side.
DriveLog HandMadeLog(double sinkage_left_m, double sinkage_right_m) {
  DriveLog log;
  log.directory = "hand-made";
  log.vehicle = sim::RockerVehicle();
  const double A = log.vehicle.axle_spacing_m, r = log.vehicle.wheel_radius_m;
  const double rim_per_s = 0.0625, advance_per_s = 0.05;
  for (int k = 0; k <= 400; ++k) {  // wheels at 10 Hz
    WheelSample w;
    w.t = 0.1 * k;
    w.omega_radps.fill(std::nan(""));
    for (int i = 0; i < 6; ++i) w.omega_radps[i] = rim_per_s / r;
    log.wheels.push_back(w);
  }
  for (int c = 0; c <= 40; ++c) {
    const double t = c, x = advance_per_s * t;
    for (Side side : {Side::kLeft, Side::kRight}) {
      const double s = side == Side::kLeft ? sinkage_left_m : sinkage_right_m;
      const auto ride = [&](double at) { return Terrain(at) - (at > 0.3 ? s : 0.0); };
      log.articulation.push_back({t, side, ride(x + A) - ride(x), ride(x + 2 * A) - ride(x)});
      for (int i = 0; i < 30; ++i) {
        const double d = 2 * A + 0.02 + 0.02 * i;
        log.range.push_back({t, side, d, Terrain(x + d) - ride(x)});
      }
    }
    TruthSample truth;
    truth.t = t;
    truth.x = x;
    truth.sinkage.fill(std::nan(""));
    truth.sinkage[0] = sinkage_left_m;
    truth.sinkage[3] = sinkage_right_m;
    log.truth.push_back(truth);
  }
  return log;
}

WilcoxOptions PointContact() {
  WilcoxOptions o;
  o.contact_patch_fraction = 0.0;
  return o;
}

TEST(WilcoxBaseline, RecoversAdvanceAndSinkageOnAHandMadeProfile) {
  const DriveLog log = HandMadeLog(0.003, 0.003);
  const WilcoxResult result = EstimateWilcoxBaseline(log, PointContact());
  ASSERT_EQ(result.sides.size(), 2u);
  for (const WilcoxSide& side : result.sides) {
    ASSERT_EQ(side.cycles.size(), 40u);
    EXPECT_NEAR(side.total_rim_m, 2.5, 1e-9);
    // Per cycle within 8 mm (the histograms' 1 cm bins and linear interpolation between ranged
    // points 2 cm apart limit a single match even without noise); the errors do not build up.
    for (const WilcoxCycle& c : side.cycles) EXPECT_NEAR(c.advance_m, 0.05, 0.008) << c.t;
    EXPECT_NEAR(side.total_advance_m, 2.0, 0.02);  // 1 % of the distance
    EXPECT_NEAR(side.cycles.back().sinkage_front_m, 0.003, 0.003);
  }
  EXPECT_TRUE(result.sides_agree) << result.agreement;
  const WilcoxScore score = ScoreWilcox(log, result);
  EXPECT_LT(score.odometry_error_fraction, 0.01);
  EXPECT_NEAR(score.rim_odometry_error_fraction, 0.25, 1e-6);
}

TEST(WilcoxBaseline, LeftRightCheckFlagsASideThatSinksMore) {
  const DriveLog log = HandMadeLog(0.013, 0.003);
  const WilcoxResult result = EstimateWilcoxBaseline(log, PointContact());
  EXPECT_FALSE(result.sides_agree) << result.agreement;
}

TEST(WilcoxBaseline, RejectsALogWithoutArticulation) {
  DriveLog log = HandMadeLog(0.003, 0.003);
  log.articulation.clear();
  EXPECT_THROW(EstimateWilcoxBaseline(log), std::invalid_argument);
}

TEST(WilcoxBaseline, SmallMonteCarloOnSimulatedRoughTerrain) {
  // Four simulated 2 cm runs, 10 % prior: measured 0.83 % mean over eight (docs/wilcox.md), the
  // rim motion alone 25 %.
  std::vector<double> errors;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox", 1)) {
    if (run.relative_directory.rfind("r2cm", 0) != 0) continue;
    if (errors.size() >= 4) break;
    const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
    errors.push_back(ScoreWilcox(log, EstimateWilcoxBaseline(log)).odometry_error_fraction);
  }
  ASSERT_EQ(errors.size(), 4u);
  for (double e : errors) EXPECT_LT(e, 0.02);
}

}  // namespace
}  // namespace slipgraph

namespace slipgraph {
namespace {

TEST(WilcoxBaseline, LeftRightCheckOnSimulatedRuns) {
  // wilcox_lr: the asymmetric runs sink 1 cm more on the left in soft patches.
  int flagged_asym = 0, flagged_sym = 0;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox_lr", 1)) {
    if (run.relative_directory != "asym_run01" && run.relative_directory != "sym_run01") continue;
    const WilcoxResult result = EstimateWilcoxBaseline(sim::Simulate(run.scenario, run.seed).log);
    (run.relative_directory == "asym_run01" ? flagged_asym : flagged_sym) += !result.sides_agree;
  }
  EXPECT_EQ(flagged_asym, 1);
  EXPECT_EQ(flagged_sym, 0);
}

}  // namespace
}  // namespace slipgraph
