// Table I's drive direction: the sign of the wheels' sum, zero within twice the still threshold;
// both wheels below that threshold; the wheels' stillness on smoothed speeds, the at-rest timer
// of both wheels and weak constraint 4's rule from the two.
#include "factors/drive_direction.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(BothWheelsStill, EachWheelBelowTheThresholdEitherWayAndNaNIsNotStill) {
  EXPECT_TRUE(BothWheelsStill(0.14, -0.14, 0.15));
  EXPECT_FALSE(BothWheelsStill(0.15, 0.0, 0.15));  // the threshold itself turns
  EXPECT_FALSE(BothWheelsStill(0.0, -0.2, 0.15));
  EXPECT_FALSE(BothWheelsStill(std::nan(""), 0.0, 0.15));
  EXPECT_FALSE(BothWheelsStill(0.0, std::nan(""), 0.15));
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

// A standing wheel whose encoder reads one count (0.153 rad/s at 100 Hz, 4096 counts a turn) on
// every fifth sample: each such reading passes the threshold, the smoothed speed (0.1 s) stays
// far below it. A wheel that starts turning at 2 rad/s reads as moving within 0.02 s.
TEST(WheelStillness, AnOddCountDoesNotEndAStopAndAStartIsSeenAtOnce) {
  const double count = 2.0 * M_PI / 4096.0 / 0.01;
  WheelStillness smoothed(0.1), each(0.0);
  WheelStopTimer smoothed_timer, each_timer;
  for (int k = 0; k <= 300; ++k) {
    const double t = 0.01 * k, omega = k % 5 == 4 ? count : 0.0;
    smoothed.Update(t, omega, 0.0);
    each.Update(t, omega, 0.0);
    smoothed_timer.Update(t, smoothed.Still(kDefaultWheelStillRadps));
    each_timer.Update(t, each.Still(kDefaultWheelStillRadps));
  }
  EXPECT_TRUE(smoothed_timer.AtRestFor(3.0, 2.9));  // at rest since the first sample
  EXPECT_FALSE(each_timer.AtRestFor(3.0, 0.05));    // restarted by every count
  double moving_after = -1.0;
  for (int k = 1; k <= 20 && moving_after < 0.0; ++k) {
    smoothed.Update(3.0 + 0.01 * k, 2.0, 2.0);
    if (!smoothed.Still(kDefaultWheelStillRadps)) moving_after = 0.01 * k;
  }
  EXPECT_GT(moving_after, 0.0);
  EXPECT_LE(moving_after, 0.02 + 1e-9);
}

// A reading that is not finite: with a time constant of 0, not still for that reading only; with
// smoothing, skipped. Neither stays stuck.
TEST(WheelStillness, AReadingThatIsNotFiniteIsNotKept) {
  WheelStillness each(0.0), smoothed(0.1);
  for (WheelStillness* s : {&each, &smoothed}) {
    s->Update(0.0, 0.0, 0.0);
    s->Update(0.01, std::nan(""), 0.0);
  }
  EXPECT_FALSE(each.Still(kDefaultWheelStillRadps));
  EXPECT_TRUE(smoothed.Still(kDefaultWheelStillRadps));
  each.Update(0.02, 0.0, 0.0);
  smoothed.Update(0.02, 0.0, 0.0);
  EXPECT_TRUE(each.Still(kDefaultWheelStillRadps));
  EXPECT_TRUE(smoothed.Still(kDefaultWheelStillRadps));
}

// Weak constraint 4's rule on the same standing wheel: with smoothing, at rest from the first
// sample except on the odd count's own cycles, which do not restart it; with none (the paper's
// test), each count restarts it. A reading that is not finite is skipped, as the EKF skips it.
TEST(WheelRestTimer, AnOddCountsOwnCycleIsNotAtRestAndDoesNotRestartTheStop) {
  const double count = 2.0 * M_PI / 4096.0 / 0.01;
  WheelRestTimer smoothed(0.1, kDefaultWheelStillRadps), each(0.0, kDefaultWheelStillRadps);
  for (int k = 0; k <= 300; ++k) {
    const double t = 0.01 * k, omega = k % 5 == 4 ? count : 0.0;
    smoothed.Update(t, omega, 0.0);
    each.Update(t, omega, 0.0);
    if (k % 5 == 4) {
      EXPECT_FALSE(smoothed.AtRestFor(t, 0.0)) << t;
      EXPECT_EQ(smoothed.StoppedFor(t), 0.0) << t;
      EXPECT_FALSE(smoothed.Timer().AtRestFor(t, 0.0)) << t;
    } else {
      EXPECT_NEAR(smoothed.StoppedFor(t), t, 1e-9);
      EXPECT_TRUE(smoothed.Timer().AtRestFor(t, t - 1e-9)) << t;
      EXPECT_LE(each.StoppedFor(t), 0.04 + 1e-9) << t;
    }
  }
  smoothed.Update(3.01, std::nan(""), 0.0);  // a lost reading: skipped, the stop goes on
  EXPECT_TRUE(smoothed.reading_still());
  EXPECT_NEAR(smoothed.StoppedFor(3.01), 3.01, 1e-9);
  smoothed.Update(3.02, 2.0, 2.0);  // a start ends it at once
  EXPECT_FALSE(smoothed.reading_still());
  EXPECT_EQ(smoothed.StoppedFor(3.02), 0.0);
}

}  // namespace
}  // namespace slipgraph
