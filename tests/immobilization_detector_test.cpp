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

}  // namespace
}  // namespace slipgraph
