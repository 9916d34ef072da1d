// Table I's drive direction: the sign of the wheels' sum, zero within twice the still threshold;
// the at-rest timer of both wheels.
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

TEST(WheelStopTimer, CountsFromTheFirstStillCycleAndRestartsOnMotion) {
  WheelStopTimer timer;
  EXPECT_EQ(timer.StoppedFor(0.0), 0.0);
  EXPECT_FALSE(timer.AtRestFor(0.0, 0.0));  // never at rest before a still reading
  timer.Update(1.0, false);
  EXPECT_FALSE(timer.AtRestFor(1.0, 0.0));
  timer.Update(2.0, true);
  timer.Update(2.5, true);  // still again: the stop began at 2.0
  EXPECT_DOUBLE_EQ(timer.StoppedFor(3.0), 1.0);
  EXPECT_TRUE(timer.AtRestFor(3.0, 1.0));
  EXPECT_FALSE(timer.AtRestFor(2.9, 1.0));
  EXPECT_TRUE(timer.AtRestFor(2.0, 0.0));
  timer.Update(3.5, false);  // moving: the count is gone
  EXPECT_EQ(timer.StoppedFor(4.0), 0.0);
  EXPECT_FALSE(timer.AtRestFor(9.0, 0.5));
  timer.Update(5.0, true);
  EXPECT_DOUBLE_EQ(timer.StoppedFor(5.25), 0.25);
}

}  // namespace
}  // namespace slipgraph
