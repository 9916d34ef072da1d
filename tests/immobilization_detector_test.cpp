#include "solvers/immobilization_detector.h"

#include <gtest/gtest.h>

#include "solvers/ema.h"

namespace slipgraph {
namespace {

TEST(Ema, MatchesEquation12) {
  ExponentialMovingAverage ema(3.0);  // weight 2 / (1 + 3) = 0.5
  EXPECT_EQ(ema.Add(4.0), 4.0);       // first sample initialises
  EXPECT_EQ(ema.Add(0.0), 2.0);       // (0 - 4) * 0.5 + 4
  EXPECT_EQ(ema.Add(2.0), 2.0);
}

TEST(ImmobilizationDetector, FlagsSustainedFullSlipOnly) {
  const ImmobilizationConfig config;
  ImmobilizationDetector d(config, 0.25, 0.55);
  // Driving normally: 5 % slip.
  for (int i = 0; i < 100; ++i) d.Update(0.95, 0.0, 4.0, 4.0, true);
  EXPECT_NEAR(d.latest().slip_left, 0.05, 1e-12);
  EXPECT_FALSE(d.latest().immobilized);
  // Held back, wheels spinning: the EMA crosses the threshold after a few samples.
  int samples = 0;
  while (!d.Update(0.0, 0.0, 4.0, 4.0, true).immobilized && samples < 100) ++samples;
  EXPECT_GT(samples, 3);   // not on the first sample: the EMA filters noise
  EXPECT_LT(samples, 30);  // within 0.3 s at 100 Hz
  EXPECT_NEAR(d.latest().threshold, config.slip_threshold, 1e-12);  // 1 m/s: no low-speed add
}

TEST(ImmobilizationDetector, NeverWhileBrakingOrWithoutFreshEncoders) {
  ImmobilizationDetector d(ImmobilizationConfig(), 0.25, 0.55);
  for (int i = 0; i < 100; ++i) d.Update(1.0, 0.0, 0.0, 0.0, true);  // skidding, wheels locked
  EXPECT_TRUE(d.latest().braking);
  EXPECT_FALSE(d.latest().immobilized);
  for (int i = 0; i < 100; ++i) d.Update(0.0, 0.0, 4.0, 4.0, false);  // encoders missing
  EXPECT_FALSE(d.latest().immobilized);
}

TEST(ImmobilizationDetector, ThresholdRisesAtLowWheelSpeed) {
  const ImmobilizationConfig config;
  ImmobilizationDetector d(config, 0.25, 0.55);
  d.Update(0.0, 0.0, 0.2, 0.2, true);  // 5 cm/s surface speed: a quarter of low_speed
  EXPECT_NEAR(d.latest().threshold,
              config.slip_threshold + config.low_speed_threshold_add * (1.0 - 0.05 / 0.2), 1e-12);
}

TEST(ImmobilizationDetector, TheVelocityMarginFlagsOnlyAConfidentlySlowBody) {
  ImmobilizationConfig config;
  config.velocity_sd_margin = 1.0;
  // Wheels at 0.5 m/s, the estimate at 0.1 m/s (slip 0.8): flagged when its sd is 0.05 (the
  // margin's velocity 0.15, slip 0.7), not when it is 0.3 (0.4, slip 0.2).
  for (const double sd : {0.05, 0.3}) {
    ImmobilizationDetector d(config, 0.25, 0.55);
    for (int i = 0; i < 100; ++i) d.Update(0.1, 0.0, 2.0, 2.0, true, sd);
    EXPECT_NEAR(d.latest().slip_ema, 0.8, 1e-9);  // the estimate's slip, unchanged by the margin
    EXPECT_EQ(d.latest().immobilized, sd < 0.1) << "sd " << sd;
  }
  // A body held still: flagged with a small sd, not with one that reaches the wheels' speed
  // (the margin moves the velocity to the surface speed at most, so the slip is 0, not braking).
  for (const double sd : {0.01, 10.0}) {
    ImmobilizationDetector held(config, 0.25, 0.55);
    for (int i = 0; i < 100; ++i) held.Update(0.0, 0.0, 2.0, 2.0, true, sd);
    EXPECT_EQ(held.latest().immobilized, sd < 1.0) << "sd " << sd;
    EXPECT_FALSE(held.latest().braking);
  }
  // Margin 0 (the default): the sd is not read.
  ImmobilizationDetector paper(ImmobilizationConfig(), 0.25, 0.55);
  for (int i = 0; i < 100; ++i) paper.Update(0.1, 0.0, 2.0, 2.0, true, 0.3);
  EXPECT_TRUE(paper.latest().immobilized);
}

}  // namespace
}  // namespace slipgraph
