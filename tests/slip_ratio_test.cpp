// The bounded slip ratio: the paper's driving slip and braking skid, the wheel spinning on a body
// at rest, and the floor below which both speeds count as zero.
#include "factors/slip_ratio.h"

#include <gtest/gtest.h>

namespace slipgraph {
namespace {

TEST(SlipRatio, DrivingIsThePapersSlip) {
  // i = 1 - v / (r w): r w = 1.0, v = 0.7.
  EXPECT_DOUBLE_EQ(SlipRatio(1.0, 0.7), 1.0 - 0.7 / 1.0);
}

TEST(SlipRatio, BrakingIsMinusThePapersSkid) {
  // i_s = 1 - r w / v: r w = 0.6, v = 1.0.
  EXPECT_DOUBLE_EQ(SlipRatio(0.6, 1.0), -(1.0 - 0.6 / 1.0));
}

TEST(SlipRatio, BoundedByOneEitherWay) {
  EXPECT_DOUBLE_EQ(SlipRatio(0.8, 0.0), 1.0);     // spinning on a body at rest
  EXPECT_DOUBLE_EQ(SlipRatio(0.0, 0.8), -1.0);    // locked wheel, body sliding
  EXPECT_DOUBLE_EQ(SlipRatio(0.5, -0.5), 2.0);    // driven forward, pushed back: beyond 1
  EXPECT_DOUBLE_EQ(SlipRatio(-1.0, -0.7), -0.3);  // reversing: the same formula, signed
}

TEST(SlipRatio, BelowTheFloorBothSpeedsCountAsZero) {
  EXPECT_DOUBLE_EQ(SlipRatio(0.0, 0.0), 0.0);
  // Below the floor the ratio is scaled by the floor, not by the tiny speeds: 0.4e-3 / 1e-3.
  EXPECT_NEAR(SlipRatio(0.5e-3, 0.1e-3), 0.4, 1e-12);
}

}  // namespace
}  // namespace slipgraph
