// Table I's drive direction: the sign of the wheels' sum, zero within twice the still threshold.
#include "factors/drive_direction.h"

#include <gtest/gtest.h>

namespace slipgraph {
namespace {

TEST(DriveDirection, SignOfTheSumWithADeadBand) {
  EXPECT_EQ(DriveDirection(2.0, 1.5, kDefaultWheelStillRadps), 1.0);
  EXPECT_EQ(DriveDirection(-2.0, -1.5, kDefaultWheelStillRadps), -1.0);
  EXPECT_EQ(DriveDirection(2.0, -2.0, kDefaultWheelStillRadps), 0.0);  // turning on the spot
  EXPECT_EQ(DriveDirection(0.14, 0.14, kDefaultWheelStillRadps), 0.0);
  EXPECT_EQ(DriveDirection(0.16, 0.16, kDefaultWheelStillRadps), 1.0);
  EXPECT_EQ(DriveDirection(0.3, 0.0, 0.15), 1.0);  // the band is open: exactly 2 x still moves
}

}  // namespace
}  // namespace slipgraph
