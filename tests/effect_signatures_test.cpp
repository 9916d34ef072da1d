// The signatures' filters (the band-pass of the mounting pitch's test) and physical limits: a
// drive's extent (99th percentiles, so a spike does not set it), each catalogue effect's
// plausible range from it, and every magnitude the simulator's catalogue uses plausible on the
// drive it hides it in.
#include "workbench/effect_signatures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "model/effect_catalogue.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace {

// A diff-drive robot of 100 kg driving at 2 m/s (wheel radius 0.25 m: 8 rad/s), turning at
// 0.4 rad/s on a 0.1 rad grade, with one absurd spike in each stream.
DriveLog SteadyDrive() {
  DriveLog log;
  log.vehicle.type = VehicleType::kDiffDriveCastor;
  log.vehicle.mass_kg = 100.0;
  log.vehicle.wheel_radius_m = 0.25;
  for (int i = 0; i < 1000; ++i) {
    const double t = 0.01 * i;
    const double w = i == 500 ? 400.0 : 8.0;
    WheelSample wheels;
    wheels.t = t;
    wheels.omega_radps[0] = wheels.omega_radps[1] = w;
    log.wheels.push_back(wheels);
    ImuSample imu;
    imu.t = t;
    imu.gz = i == 500 ? 30.0 : 0.4;
    log.imu.push_back(imu);
    AttitudeSample a;
    a.t = t;
    a.pitch = i == 500 ? 1.5 : -0.1;
    log.attitude.push_back(a);
  }
  return log;
}

PlausibleRange RangeOf(const std::string& effect, const DriveLog& log) {
  const EffectSignature* s = EffectRegistry::Catalogue().FindSignature(effect);
  EXPECT_NE(s, nullptr) << effect;
  EXPECT_TRUE(s != nullptr && s->plausible) << effect;
  return s != nullptr && s->plausible ? s->plausible(log) : PlausibleRange{};
}

TEST(EffectSignatures, TheBandPassKeepsSecondsAndLeavesOutADriftAndAVibration) {
  // 100 s at 100 Hz: a drift of 0.01 a second, a swing of period 2 s and a 12 Hz vibration.
  std::vector<double> t, drift, swing, vibration;
  for (int i = 0; i < 10000; ++i) {
    t.push_back(0.01 * i);
    drift.push_back(0.01 * t.back());
    swing.push_back(std::sin(M_PI * t.back()));
    vibration.push_back(std::sin(24.0 * M_PI * t.back()));
  }
  const auto rms_inside = [&](const std::vector<double>& x) {  // away from the ends' 3 s
    double sum = 0.0;
    int count = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      if (t[i] < 3.0 || t[i] > 97.0) continue;
      sum += x[i] * x[i];
      ++count;
    }
    return std::sqrt(sum / count);
  };
  // A centred average takes a straight line through its own value: the drift is gone (but for
  // a sample more on one side where the stamps' rounding decides, 1e-5 here).
  EXPECT_LT(rms_inside(BandPass(t, drift, 0.5, 5.0)), 1e-4);
  // A 2 s period passes at 0.77 of its amplitude (sinc(1/4) - sinc(5/2)); 12 Hz at a few percent.
  EXPECT_NEAR(rms_inside(BandPass(t, swing, 0.5, 5.0)), 0.773 / std::sqrt(2.0), 0.01);
  EXPECT_LT(rms_inside(BandPass(t, vibration, 0.5, 5.0)), 0.03);
  // The high-pass keeps the vibration whole.
  EXPECT_NEAR(rms_inside(HighPass(t, vibration, 5.0)), 1.0 / std::sqrt(2.0), 0.01);
}

TEST(EffectSignatures, ExtentIgnoresASpike) {
  const DriveExtent e = ExtentOf(SteadyDrive());
  EXPECT_NEAR(e.weight_n, 980.665, 1e-9);
  EXPECT_NEAR(e.speed_mps, 2.0, 1e-12);
  EXPECT_NEAR(e.yaw_rate_radps, 0.4, 1e-12);
  EXPECT_NEAR(e.grade_rad, 0.1, 1e-12);
}

TEST(EffectSignatures, ForcesOpposeMotionUpToHalfTheWeight) {
  const DriveLog log = SteadyDrive();
  const double half_weight = 0.5 * 980.665;
  // Drag: theta v^2 <= W / 2 at 2 m/s; it cannot push.
  const PlausibleRange drag = RangeOf("quadratic_drag", log);
  EXPECT_EQ(drag.low, 0.0);
  EXPECT_NEAR(drag.high, half_weight / 4.0, 1e-9);
  EXPECT_NE(drag.basis.find("2 m/s"), std::string::npos) << drag.basis;
  // Turn slip: theta W |yaw rate| <= W / 2 at 0.4 rad/s.
  const PlausibleRange turn = RangeOf("turn_slip", log);
  EXPECT_EQ(turn.low, 0.0);
  EXPECT_NEAR(turn.high, 0.5 / 0.4, 1e-12);
  EXPECT_EQ(RangeOf("sinkage_resistance", log).high, 0.5);
  // Slope slip: the traction changed by at most 90 % on the 0.1 rad grade, either way.
  const PlausibleRange slope = RangeOf("slope_slip", log);
  EXPECT_NEAR(slope.high, 9.0, 1e-12);
  EXPECT_NEAR(slope.low, -9.0, 1e-12);
}

TEST(EffectSignatures, AFlatStraightStandstillLeavesTheForcesUnbounded) {
  DriveLog log = SteadyDrive();
  for (WheelSample& w : log.wheels) w.omega_radps.fill(0.0);
  for (ImuSample& imu : log.imu) imu.gz = 0.0;
  for (AttitudeSample& a : log.attitude) a.pitch = 0.0;
  EXPECT_TRUE(std::isinf(RangeOf("quadratic_drag", log).high));
  EXPECT_TRUE(std::isinf(RangeOf("turn_slip", log).high));
  EXPECT_TRUE(std::isinf(RangeOf("slope_slip", log).high));
}

TEST(EffectSignatures, TheCataloguesMagnitudesArePlausibleOnTheirDrives) {
  for (const EffectInfo& effect : EffectCatalogue()) {
    if (!effect.in_model_catalogue) continue;
    const sim::ScenarioRun run = sim::ExpandScenario("hidden/" + effect.name, 1).at(0);
    const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
    const PlausibleRange r = RangeOf(effect.name, log);
    EXPECT_GE(effect.default_value, r.low) << effect.name << ": " << r.basis;
    EXPECT_LE(effect.default_value, r.high) << effect.name << ": " << r.basis;
    // With room to spare: half as much again is still plausible.
    EXPECT_LE(1.5 * effect.default_value, r.high) << effect.name << ": " << r.basis;
  }
}

}  // namespace
}  // namespace slipgraph
