// The mismatch suites' truth (sim/peaked_tire.h, docs/mismatch.md): the peaked traction law
// against hand-computed values, and the suites' scenarios against what the docs promise.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "sim/peaked_tire.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace {

sim::PeakedSoil Soil() {
  sim::PeakedSoil soil;
  soil.peak_mu = 0.6;
  soil.stiffness_b = 10.0;
  soil.shape_c = 1.6;
  soil.curvature_e = 0.0;
  soil.roll_c0 = 0.05;
  soil.roll_c1_spm = 0.02;
  return soil;
}

TEST(PeakedTire, HandComputedForceAndItsPeakAndFall) {
  const sim::PeakedSoil soil = Soil();
  // kappa = 0.05: B kappa = 0.5, atan 0.5 = 0.463648, 1.6 x = 0.741836, sin = 0.675643.
  EXPECT_NEAR(sim::PeakedTractionForceN(1000.0, 0.05, soil), 1000.0 * 0.6 * 0.675643, 1e-3);
  // The peak where C atan(B kappa) = pi/2: kappa = tan(pi / 3.2) / 10 = 0.0668179.
  const double peak = std::tan(M_PI / 3.2) / 10.0;
  EXPECT_NEAR(sim::PeakedTractionForceN(1000.0, peak, soil), 600.0, 1e-6);
  EXPECT_LT(sim::PeakedTractionForceN(1000.0, peak + 0.01, soil), 600.0);
  // A spinning wheel pulls less than the peak (the falling branch eq. 8 does not have).
  EXPECT_LT(sim::PeakedTractionForceN(1000.0, 1.0, soil), 0.95 * 600.0);
  // Odd in the slip ratio: braking mirrors driving.
  EXPECT_DOUBLE_EQ(sim::PeakedTractionForceN(1000.0, -0.3, soil),
                   -sim::PeakedTractionForceN(1000.0, 0.3, soil));
}

TEST(PeakedTire, SlipRatioIsFiniteAtRestAndRelaxesOverItsLength) {
  EXPECT_DOUBLE_EQ(sim::SteadySlipRatio(0.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(sim::SteadySlipRatio(0.5, 0.0), 1.0);           // spinning in place
  EXPECT_DOUBLE_EQ(sim::SteadySlipRatio(0.01, 0.0), 0.01 / 0.05);  // below the floor
  EXPECT_NEAR(sim::SteadySlipRatio(1.0, 0.9), 0.1, 1e-12);         // driving
  EXPECT_NEAR(sim::SteadySlipRatio(0.9, 1.0), -0.1, 1e-12);        // braking
  // At 1 m/s over a 0.2 m relaxation length: a time constant of 0.2 / 1.05 s; after it, 1 - 1/e.
  double kappa = 0.0;
  const double dt = 1e-4, tau = 0.2 / 1.05;
  for (double t = 0.0; t < tau - 0.5 * dt; t += dt)
    kappa = sim::RelaxSlipRatio(kappa, 0.1, 1.0, 0.9, 0.2, dt);
  EXPECT_NEAR(kappa, 0.1 * (1.0 - std::exp(-1.0)), 2e-4);
}

TEST(PeakedTire, RollingResistanceOpposesMotionAndGrowsWithSpeed) {
  const sim::PeakedSoil soil = Soil();
  EXPECT_DOUBLE_EQ(sim::PeakedRollingForceN(1000.0, 0.0, soil), 0.0);
  EXPECT_NEAR(sim::PeakedRollingForceN(1000.0, 1.0, soil), -1000.0 * 0.07, 1e-6);
  EXPECT_NEAR(sim::PeakedRollingForceN(1000.0, -1.0, soil), 1000.0 * 0.07, 1e-6);
}

TEST(MismatchSuites, SameDrivesAsTheMatchedOnesWithSoilsTheModelDoesNotHave) {
  const std::vector<sim::ScenarioRun> matched = sim::ExpandScenario("ward21", 3);
  const std::vector<sim::ScenarioRun> mismatch = sim::ExpandScenario("ward21m", 3);
  ASSERT_EQ(mismatch.size(), matched.size());
  std::set<double> peaks;
  for (size_t i = 0; i < matched.size(); ++i) {
    const sim::Scenario& a = matched[i].scenario;
    const sim::Scenario& b = mismatch[i].scenario;
    EXPECT_EQ(b.name.substr(0, 8), "ward21m/");
    EXPECT_EQ(b.duration_s(), a.duration_s());
    ASSERT_EQ(b.holdbacks.size(), a.holdbacks.size());
    for (size_t h = 0; h < a.holdbacks.size(); ++h) {
      EXPECT_EQ(b.holdbacks[h].t_start_s, a.holdbacks[h].t_start_s);
    }
    EXPECT_FALSE(a.vehicle.law_samples.empty());
    EXPECT_TRUE(b.vehicle.law_samples.empty());  // one nominal law, as for a new robot
    ASSERT_FALSE(b.course.patches.empty());
    for (size_t p = 0; p < b.course.patches.size(); ++p) {
      const sim::TerrainPatch& patch = b.course.patches[p];
      ASSERT_TRUE(patch.terrain.peaked.has_value());
      EXPECT_GE(patch.terrain.peaked->peak_mu, 0.30);
      EXPECT_LE(patch.terrain.peaked->peak_mu, 0.90);
      peaks.insert(patch.terrain.peaked->peak_mu);
      if (p > 1) {
        const double length = patch.s_start_m - b.course.patches[p - 1].s_start_m;
        EXPECT_GE(length, 10.0);
        EXPECT_LE(length, 40.0);
      }
    }
    EXPECT_GT(b.sensors.mismatch.vibration_sd_mps2_per_mps, 0.0);
    EXPECT_TRUE(b.sensors.mismatch.gps_velocity_interval_mean);
    EXPECT_GT(b.sensors.mismatch.attitude_error_sd_rad, 0.0);
  }
  EXPECT_GT(peaks.size(), 15u);  // a soil of its own per run at least
}

// A held robot rocking on its tether (the peaked law's falling branch) lifts its speed above the
// truth's stopped threshold for a few samples: still one immobilization (stops less than 0.5 s
// apart are one event). On high-friction soil the torque-limited wheels stall instead of
// spinning: no immobilization at all (fig5m seeds 1-10: 4 hold-backs spin, 6 stall).
TEST(MismatchSuites, AHoldBackIsAtMostOneEvent) {
  int spinning = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    const sim::ScenarioRun run = sim::ExpandScenario("fig5m", seed).at(0);
    const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
    ASSERT_LE(log.events.size(), 1u) << seed;
    if (log.events.empty()) continue;
    ++spinning;
    EXPECT_GT(log.events[0].t_start, run.scenario.holdbacks[0].t_start_s) << seed;
    EXPECT_LT(log.events[0].t_end, run.scenario.holdbacks[0].t_end_s + 0.5) << seed;
  }
  EXPECT_EQ(spinning, 4);
}

// The chassis vibration's sd at a steady 1 m/s: 0.25 m/s^2 on top of the sensor's white noise
// (0.05), measured as the sd of the accelerometer's x about its mean over 10 s.
TEST(MismatchSuites, VibrationIsAQuarterMetrePerSecondSquaredAtOneMetrePerSecond) {
  sim::Scenario sc = sim::ExpandScenario("fig5m", 1).at(0).scenario;
  sc.holdbacks.clear();
  sc.commands = {{14.0, 1.0, 0.0}};
  sc.course.hills.clear();
  const DriveLog log = sim::Simulate(sc, 1).log;
  double sum = 0.0, sum_sq = 0.0;
  int n = 0;
  for (const ImuSample& imu : log.imu) {
    if (imu.t < 6.0 || imu.t > 16.0) continue;
    sum += imu.ax, sum_sq += imu.ax * imu.ax, ++n;
  }
  ASSERT_GT(n, 900);
  const double sd = std::sqrt(sum_sq / n - (sum / n) * (sum / n));
  // 1000 samples of a resonance correlated over about 0.3 s: the sd is known to about 10 %.
  EXPECT_NEAR(sd, std::hypot(0.25, 0.05), 0.04);
}

}  // namespace
}  // namespace slipgraph
