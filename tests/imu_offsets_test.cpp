#include "solvers/imu_offsets.h"

#include <gtest/gtest.h>

namespace slipgraph {
namespace {

TEST(ImuOffsets, MeanOfFirstSamplesWithGravityRemovedThenEmaAtRestOnly) {
  ImuOffsetEstimator offsets(4, 3.0);
  // On a slope the accelerometer reads g sin(phi) = 0.5 plus the offset 0.1.
  for (int i = 0; i < 3; ++i) offsets.Add(0.6, 0.01, 0.5, false);
  EXPECT_FALSE(offsets.ready());
  offsets.Add(0.6, 0.03, 0.5, false);
  ASSERT_TRUE(offsets.ready());
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);
  EXPECT_NEAR(offsets.gyro_z_radps(), 0.015, 1e-12);
  offsets.Add(5.0, 1.0, 0.0, false);  // moving: ignored
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.1, 1e-12);
  offsets.Add(0.3, 0.015, 0.0, true);  // at rest: EMA with weight 0.5
  EXPECT_NEAR(offsets.accel_x_mps2(), 0.2, 1e-12);
}

}  // namespace
}  // namespace slipgraph
