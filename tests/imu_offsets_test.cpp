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

}  // namespace
}  // namespace slipgraph
