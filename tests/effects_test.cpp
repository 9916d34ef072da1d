// Each catalogue effect does, in the simulator, what its documentation says.
#include "sim/effects.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

using testing::FlatLagrScenario;
using testing::MeanTruth;

constexpr double kG = 9.80665;

sim::SimResult RunWith(sim::Scenario sc, const std::string& effect, double value,
                       uint64_t seed = 4) {
  if (!effect.empty()) sc.effects[effect] = value;
  return sim::Simulate(sc, seed);
}

TEST(Effects, CatalogueIsCompleteAndParses) {
  for (const char* name : {"gps_velocity_averaging", "wheel_radius_error", "imu_mounting_pitch",
                           "slope_slip", "turn_slip", "sinkage_resistance", "quadratic_drag",
                           "load_transfer", "terrain_change", "clock_offset"}) {
    const sim::EffectInfo* info = sim::FindEffect(name);
    ASSERT_NE(info, nullptr) << name;
    EXPECT_TRUE(info->in_model_catalogue);
    EXPECT_FALSE(info->physics.empty());
    EXPECT_FALSE(info->evidence.empty());
  }
  sim::EffectSet set;
  std::string error;
  EXPECT_TRUE(sim::ParseEffect("quadratic_drag=12.5", &set, &error));
  EXPECT_EQ(set["quadratic_drag"], 12.5);
  EXPECT_TRUE(sim::ParseEffect("clock_offset", &set, &error));
  EXPECT_EQ(set["clock_offset"], 0.05);
  EXPECT_FALSE(sim::ParseEffect("warp_drive", &set, &error));
  EXPECT_NE(error.find("unknown effect 'warp_drive'"), std::string::npos);
  EXPECT_FALSE(sim::ParseEffect("quadratic_drag=lots", &set, &error));
}

TEST(Effects, QuadraticDragIsAResistiveDisturbance) {
  const sim::SimResult r = RunWith(FlatLagrScenario("gravel", 1.0, 10.0), "quadratic_drag", 40.0);
  const double v = MeanTruth(r.log, 8.0, 11.0, [](const auto& s) { return s.vx; });
  EXPECT_NEAR(MeanTruth(r.log, 8.0, 11.0, [](const auto& s) { return s.a_dist; }),
              -40.0 * v * v / 117.0, 0.005);
}

TEST(Effects, TurnSlipResistsOnlyWhileTurning) {
  sim::Scenario sc = FlatLagrScenario("gravel", 0.8, 6.0);
  sc.commands.push_back({6.0, 0.8, 0.5});
  const sim::SimResult r = RunWith(sc, "turn_slip", 0.15);
  EXPECT_NEAR(MeanTruth(r.log, 5.0, 7.5, [](const auto& s) { return s.a_dist; }), 0.0, 1e-9);
  const double yaw_rate = MeanTruth(r.log, 11.0, 13.5, [](const auto& s) { return s.yaw_rate; });
  EXPECT_GT(yaw_rate, 0.4);
  EXPECT_NEAR(MeanTruth(r.log, 11.0, 13.5, [](const auto& s) { return s.a_dist; }),
              -0.15 * kG * yaw_rate, 0.02);
}

TEST(Effects, SinkageResistanceActsOnSoftTerrainOnly) {
  sim::Scenario sc = FlatLagrScenario("gravel", 0.8, 12.0);
  sc.course.patches.push_back({4.0, sim::FindTerrain("mud")});
  const sim::SimResult r = RunWith(sc, "sinkage_resistance", 0.08);
  EXPECT_NEAR(MeanTruth(r.log, 4.0, 6.0, [](const auto& s) { return s.a_dist; }), 0.0, 1e-9);
  // Well inside the mud patch (s > 4.5 m) the full 0.08 g opposes motion.
  EXPECT_NEAR(MeanTruth(r.log, 12.0, 14.0, [](const auto& s) { return s.a_dist; }), -0.08 * kG,
              0.01);
}

TEST(Effects, WheelRadiusErrorScalesEncoderSpeed) {
  const sim::Scenario sc = FlatLagrScenario("asphalt", 1.0, 8.0);
  const sim::SimResult base = RunWith(sc, "", 0.0);
  const sim::SimResult bigger = RunWith(sc, "wheel_radius_error", 0.05);
  EXPECT_DOUBLE_EQ(bigger.true_wheel_radius_m, 0.25 * 1.05);
  // Same commanded wheel speed, 5 % more ground speed.
  const double v0 = MeanTruth(base.log, 7.0, 9.5, [](const auto& s) { return s.vx; });
  const double v1 = MeanTruth(bigger.log, 7.0, 9.5, [](const auto& s) { return s.vx; });
  EXPECT_NEAR(v1 / v0, 1.05, 0.01);
}

TEST(Effects, ImuMountingPitchLeaksGravityIntoX) {
  sim::Scenario sc = FlatLagrScenario("gravel", 0.0, 1.0);
  sc.sensors.sd_accel_mps2 = 0.0;
  sc.sensors.accel_bias_sd_mps2 = 0.0;
  const sim::SimResult r = RunWith(sc, "imu_mounting_pitch", 0.03);
  // At rest on flat ground: ax = -g sin(delta) + c_ax (nose-down sensor sees gravity backward).
  EXPECT_NEAR(r.log.imu[10].ax - r.imu_errors.accel_offset_mps2[0], -kG * std::sin(0.03), 1e-9);
  EXPECT_NEAR(r.log.imu[10].az - r.imu_errors.accel_offset_mps2[2], kG * std::cos(0.03), 1e-9);
}

TEST(Effects, ClockOffsetDelaysImuStamps) {
  const sim::SimResult r = RunWith(FlatLagrScenario("gravel", 0.5, 1.0), "clock_offset", 0.05);
  EXPECT_DOUBLE_EQ(r.log.imu[0].t, 0.05);
  EXPECT_DOUBLE_EQ(r.log.wheels[0].t, 0.0);
}

TEST(Effects, GpsVelocityAveragingLagsWhileAccelerating) {
  sim::Scenario sc = FlatLagrScenario("asphalt", 1.0, 4.0);
  sc.sensors.gps_sd_v_mps = 0.0;
  const sim::SimResult instant = RunWith(sc, "", 0.0, 9);
  const sim::SimResult averaged = RunWith(sc, "gps_velocity_averaging", 1.0, 9);
  // Fix at t = 3 s: accelerating since t = 2 s, the averaged velocity is the mean over [2, 3].
  const GpsSample& a = instant.log.gps[3];
  const GpsSample& b = averaged.log.gps[3];
  ASSERT_DOUBLE_EQ(b.t, 3.0);
  EXPECT_LT(b.vx, a.vx - 0.2);
  const double mean_speed = (averaged.log.truth[300].x - averaged.log.truth[200].x) / 1.0;
  EXPECT_NEAR(b.vx, mean_speed, 1e-9);
}

TEST(Effects, SlopeSlipIncreasesSlipOnHills) {
  sim::Scenario sc = FlatLagrScenario("gravel", 0.5, 16.0);
  sc.course.hills = {{-100.0, 200.0, 0.10, 0.0}};
  const auto slip = [](const sim::SimResult& r) {
    return MeanTruth(r.log, 12.0, 16.0, [](const auto& s) { return s.slip[0]; });
  };
  const double base = slip(RunWith(sc, "", 0.0));
  const double with = slip(RunWith(sc, "slope_slip", 4.0));
  EXPECT_GT(with, 1.5 * base);  // C1 x (1 - 0.4): much more slip for the same pull
}

TEST(Effects, TerrainChangeHalfwayIncreasesSlip) {
  const sim::Scenario sc = FlatLagrScenario("gravel", 0.8, 20.0);  // 22 s log: change at 11 s
  const sim::SimResult r = RunWith(sc, "terrain_change", 0.6);
  const double before = MeanTruth(r.log, 7.0, 10.5, [](const auto& s) { return s.slip[0]; });
  const double after = MeanTruth(r.log, 13.0, 21.0, [](const auto& s) { return s.slip[0]; });
  EXPECT_GT(after, 1.3 * before);
}

TEST(Effects, LoadTransferUnloadsTheFrontWheelsWhileAccelerating) {
  // Front-wheel drive: under acceleration the driven wheels lose load, so more slip.
  const sim::Scenario sc = FlatLagrScenario("gravel", 1.2, 4.0);
  const auto slip = [](const sim::SimResult& r) {
    return MeanTruth(r.log, 2.2, 3.2, [](const auto& s) { return s.slip[0]; });
  };
  EXPECT_GT(slip(RunWith(sc, "load_transfer", 1.0)), slip(RunWith(sc, "", 0.0)) * 1.02);
}

TEST(Effects, CorrugationIsPeriodicInDistance) {
  const sim::SimResult r = RunWith(FlatLagrScenario("asphalt", 1.0, 8.0), "corrugation", 0.6);
  double max_a = 0.0, min_a = 0.0;
  for (const TruthSample& s : r.log.truth) {
    if (s.t > 4.0) max_a = std::max(max_a, s.a_dist), min_a = std::min(min_a, s.a_dist);
  }
  EXPECT_NEAR(max_a, 0.6, 0.01);
  EXPECT_NEAR(min_a, -0.6, 0.01);
}

}  // namespace
}  // namespace slipgraph
