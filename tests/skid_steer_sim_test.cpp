#include "sim/skid_steer_sim.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/scenarios.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

using testing::MeanTruth;

// A flat course of one terrain with a known, noise-free slip model.
sim::Scenario TrackedScenario(double v, double w) {
  sim::Scenario sc;
  sc.name = "test";
  sc.vehicle = sim::TrackedVehicle();
  sc.sim_step_s = 0.001;
  sim::TerrainType terrain = sim::FindTerrain("soft_dirt");
  terrain.ipd.q_density = {0.0, 0.0, 0.0};
  sc.course.patches = {{0.0, terrain}};
  sc.rest_start_s = 1.0;
  sc.commands = {{8.0, v, w}};
  sc.sensors.gps_rate_hz = 0.0;
  sc.sensors.pose_rate_hz = 10.0;
  return sc;
}

TEST(SkidSteerSim, SteadyMotionFollowsTheSlipModel) {
  // Steady v_n = 1 m/s, w_n = 0.5 rad/s on flat soft dirt: u = u_n + C(u_n, 0) alpha.
  const sim::Scenario sc = TrackedScenario(1.0, 0.5);
  const sim::SimResult r = sim::SimulateSkidSteer(sc, 1);
  const auto& a = sc.course.patches[0].terrain.ipd.alpha;
  const double v = 1.0, w = 0.5;
  EXPECT_NEAR(MeanTruth(r.log, 6.0, 9.0, [](const auto& s) { return s.vx; }),
              v + a[0] * v + a[1] * w + a[2] * v * w, 1e-3);
  EXPECT_NEAR(MeanTruth(r.log, 6.0, 9.0, [](const auto& s) { return s.vy; }),
              a[4] * v + a[5] * w + a[6] * v * w, 1e-3);
  EXPECT_NEAR(MeanTruth(r.log, 6.0, 9.0, [](const auto& s) { return s.yaw_rate; }),
              w + a[8] * v + a[9] * w + a[10] * v * w, 1e-3);
  // Track slip: the left track (inside of the turn) and right both slip forward on soft dirt.
  EXPECT_GT(MeanTruth(r.log, 6.0, 9.0, [](const auto& s) { return s.slip[1]; }), 0.0);
}

TEST(SkidSteerSim, PoseIntegratesTheTrueVelocity) {
  const sim::Scenario sc = TrackedScenario(1.2, 0.0);
  const sim::SimResult r = sim::SimulateSkidSteer(sc, 1);
  ASSERT_FALSE(r.log.pose.empty());
  // Straight line: distance = integral of truth vx.
  double distance = 0.0;
  for (size_t i = 1; i < r.log.truth.size(); ++i) {
    distance += 0.5 * (r.log.truth[i].vx + r.log.truth[i - 1].vx) * 0.01;
  }
  EXPECT_NEAR(r.log.truth.back().x, distance, 0.01);
  EXPECT_NEAR(r.log.pose.back().x, r.log.truth.back().x, 0.1);  // pose sd 2 cm
}

TEST(SkidSteerSim, StochasticSlipHasTheTerrainsDensity) {
  // Heading random walk over straight driving: var(yaw(T) - yaw(0) - mean) ~= q_yaw T.
  sim::Scenario sc = TrackedScenario(1.0, 0.0);
  sim::TerrainType terrain = sim::FindTerrain("soft_dirt");
  sc.course.patches = {{0.0, terrain}};
  sc.commands = {{400.0, 1.0, 0.0}};
  const sim::SimResult r = sim::SimulateSkidSteer(sc, 9);
  // Heading increments over 2 s windows, after the start-up.
  std::vector<double> increments;
  for (size_t i = 300; i + 200 < r.log.truth.size(); i += 200) {
    increments.push_back(r.log.truth[i + 200].yaw - r.log.truth[i].yaw);
  }
  double mean = 0.0, var = 0.0;
  for (double d : increments) mean += d;
  mean /= increments.size();
  for (double d : increments) var += (d - mean) * (d - mean);
  var /= increments.size() - 1;
  // 200 windows: the sample variance is within ~20 % of q T at 2 sigma; the Gauss-Markov
  // correlation (0.1 s) shortens the effective window by ~5 %.
  EXPECT_NEAR(var, terrain.ipd.q_density[2] * 2.0, 0.3 * terrain.ipd.q_density[2] * 2.0);
}

}  // namespace
}  // namespace slipgraph
