#include "solvers/imu_offsets.h"

#include <gtest/gtest.h>

namespace slipgraph {
namespace {

TEST(ImuOffsets, MeanOfFirstSamplesWithGravityRemovedThenEmaAtRestOnly) {
  ImuOffsetEstimator offsets(4, 3.0);
  // On a slope the accelerometer reads g sin(phi) = 0.5 plus the offset 0.1.
  for (int i = 0; i < 3; ++i) offsets.Add(0.0, 0.6, 0.01, 0.5, false);
  EXPECT_FALSE(offsets.ready());
  offsets.Add(0.0, 0.6, 0.03, 0.5, false);
  ASSERT_TRUE(offsets.ready());
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);
  EXPECT_NEAR(offsets.gyro_z_radps(), 0.015, 1e-12);
  offsets.Add(0.0, 5.0, 1.0, 0.0, false);  // moving: ignored
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);
  offsets.Add(0.0, 0.3, 0.015, 0.0, true);  // at rest: EMA with weight 0.5
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.2, 1e-12);
}

TEST(ImuOffsets, AtRestSamplesWaitTheGuardAndAreDroppedWhenMotionFollows) {
  ImuOffsetEstimator offsets(1, 3.0, 0.5);  // EMA weight 0.5, guard 0.5 s
  offsets.Add(0.0, 0.1, 0.0, 0.0, true);
  ASSERT_TRUE(offsets.ready());
  // The encoders still read zero while the body creeps off: these carry its acceleration.
  for (int i = 1; i <= 10; ++i) offsets.Add(0.01 * i, 0.5, 0.0, 0.0, true);
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);  // not yet older than the guard
  offsets.Add(0.11, 0.6, 0.0, 0.0, false);          // motion seen: the waiting samples go
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);
  // A long rest: each sample enters once the rest has lasted the guard after it.
  offsets.Add(2.0, 0.3, 0.0, 0.0, true);
  offsets.Add(2.4, 0.1, 0.0, 0.0, true);
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);
  offsets.Add(2.5, 0.1, 0.0, 0.0, true);  // 2.0 is now 0.5 s old
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.2, 1e-12);
}

TEST(ImuOffsets, AMovingStartSubtractsTheWheelsAccelerationAndYawRate) {
  // 100 samples over 1 s: offsets 0.1 m/s^2 and 0.01 rad/s; the body accelerates at 0.5 m/s^2
  // and turns at 0.2 rad/s throughout, and the wheels see both.
  ImuOffsetEstimator offsets(100, 200.0);
  for (int i = 0; i < 100; ++i) {
    const double t = 0.01 * i;
    offsets.Add(t, 0.1 + 0.5, 0.01 + 0.2, 0.0, false, {0.5 * t, 0.2, false});
  }
  ASSERT_TRUE(offsets.ready());
  EXPECT_TRUE(offsets.moving_start());
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-9);
  EXPECT_NEAR(offsets.gyro_z_radps(), 0.01, 1e-12);
  EXPECT_NEAR(offsets.init_sd()[0], 0.1 + 0.05, 1e-9);
  EXPECT_NEAR(offsets.init_sd()[1], 0.04, 1e-12);

  // Control: the same samples with the wheels still (a rest start) keep the plain mean, which
  // carries the motion.
  ImuOffsetEstimator at_rest(100, 200.0);
  for (int i = 0; i < 100; ++i) at_rest.Add(0.01 * i, 0.6, 0.21, 0.0, true, {0.0, 0.0, true});
  EXPECT_FALSE(at_rest.moving_start());
  EXPECT_NEAR(at_rest.accel_x_mps2(), 0.6, 1e-12);
  EXPECT_EQ(at_rest.init_sd()[0], 0.0);
}

TEST(ImuOffsets, ARestShorterThanTheInitialSamplesIsUsedWhenTheWheelsTurn) {
  // 100 initial samples at 100 Hz; the wheels turn at 0.5 s. The rest's samples but the last
  // tenth of a second (0.41 s and later carry the start the encoders have not seen yet).
  ImuOffsetEstimator offsets(100, 200.0);
  for (int i = 0; i < 50; ++i) {
    const double t = 0.01 * i;
    offsets.Add(t, t < 0.405 ? 0.1 : 0.5, 0.01, 0.0, true, {0.0, 0.0, true});
  }
  EXPECT_FALSE(offsets.ready());
  offsets.Add(0.5, 0.9, 0.01, 0.0, false, {0.05, 0.0, false});
  ASSERT_TRUE(offsets.ready());
  EXPECT_FALSE(offsets.moving_start());
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);

  // Too short a rest (0.2 s < 100 / 4 samples): the motion is compensated over 100 samples.
  ImuOffsetEstimator short_rest(100, 200.0);
  for (int i = 0; i < 20; ++i) short_rest.Add(0.01 * i, 0.1, 0.0, 0.0, true, {0.0, 0.0, true});
  for (int i = 20; i < 100; ++i) {
    const double t = 0.01 * i;
    short_rest.Add(t, 0.1 + 0.5, 0.0, 0.0, false, {0.5 * (t - 0.195), 0.0, false});
  }
  ASSERT_TRUE(short_rest.ready());
  EXPECT_TRUE(short_rest.moving_start());
  EXPECT_NEAR(short_rest.accel_x_mps2(), 0.1, 0.02);
}

TEST(ImuOffsets, AnImplausibleCompensatedOffsetStartsAtZero) {
  // Held back from the first sample: the wheels keep their speed while the body decelerates at
  // 0.7 m/s^2. The compensated offset (-0.6) is no sensor's: zero, with a typical offset's sd.
  ImuOffsetEstimator offsets(100, 200.0);
  for (int i = 0; i < 100; ++i)
    offsets.Add(0.01 * i, 0.1 - 0.7, 0.0, 0.0, false, {1.0, 0.0, false});
  ASSERT_TRUE(offsets.ready());
  EXPECT_TRUE(offsets.implausible_start());
  EXPECT_EQ(offsets.accel_x_mps2(), 0.0);
  EXPECT_NEAR(offsets.init_sd()[0], 0.3, 1e-12);
}

TEST(ImuOffsets, SamplesBeforeTheWheelsFirstReadingAreNeitherRestNorMotion) {
  // The IMU starts 0.3 s before the encoders on a robot already accelerating at 0.5 m/s^2:
  // those samples are not a rest, and the motion is compensated over the ones the wheels saw.
  ImuOffsetEstimator offsets(100, 200.0);
  for (int i = 0; i < 100; ++i) {
    const double t = 0.01 * i;
    const WheelMotion wheels = t < 0.295 ? WheelMotion{} : WheelMotion{1.0 + 0.5 * t, 0.0, false};
    offsets.Add(t, 0.1 + 0.5, 0.0, 0.0, false, wheels);
  }
  ASSERT_TRUE(offsets.ready());
  EXPECT_TRUE(offsets.moving_start());
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-9);
}

}  // namespace
}  // namespace slipgraph
