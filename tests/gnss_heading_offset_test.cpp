// The attitude's yaw against the GNSS course: an offset found from noisy fixes, driving forwards
// or backwards; left at zero where the yaw agrees within noise, before enough fixes, and from
// fixes too slow or with the wheels still; never from the fix it is applied to.
#include "factors/gnss_heading_offset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace slipgraph {
namespace {

// Fixes of a robot driving at `speed` (m/s, negative: backwards) on a heading that turns
// slowly, whose attitude's yaw is `offset` short of the course; velocity noise sd_v per axis.
GnssHeadingOffset Drive(double offset, double speed, double sd_v, int fixes, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sd_v);
  GnssHeadingOffset heading;
  for (int i = 0; i < fixes; ++i) {
    const double yaw = 0.02 * i;
    const double course = yaw + offset + (speed < 0.0 ? M_PI : 0.0);
    const double ve = std::abs(speed) * std::cos(course) + noise(rng);
    const double vn = std::abs(speed) * std::sin(course) + noise(rng);
    heading.Observe(ve, vn, sd_v, yaw, speed / 0.2);
  }
  return heading;
}

TEST(GnssHeadingOffset, FindsAYawOffFromTheCourse) {
  for (uint64_t seed : {1, 2, 3}) {
    for (double offset : {0.35, -0.5}) {
      for (double speed : {1.0, -0.8}) {
        const GnssHeadingOffset heading = Drive(offset, speed, 0.1, 60, seed);
        EXPECT_EQ(heading.fixes_counted(), 60);
        EXPECT_NEAR(heading.offset_rad(), offset, 0.06) << seed << " " << speed;
        EXPECT_LT(heading.sd_rad(), 0.05);
      }
    }
  }
}

TEST(GnssHeadingOffset, LeavesAYawThatAgreesWithinNoise) {
  for (uint64_t seed : {1, 2, 3, 4, 5}) {
    const GnssHeadingOffset heading = Drive(0.01, 1.0, 0.1, 200, seed);
    EXPECT_NEAR(heading.mean_rad(), 0.01, 0.06);
    EXPECT_EQ(heading.offset_rad(), 0.0) << seed;
  }
}

TEST(GnssHeadingOffset, WaitsForEnoughFixes) {
  EXPECT_EQ(Drive(0.5, 1.0, 0.05, 4, 1).offset_rad(), 0.0);
  EXPECT_NEAR(Drive(0.5, 1.0, 0.05, 5, 1).offset_rad(), 0.5, 0.1);
}

TEST(GnssHeadingOffset, CountsOnlyFixesThatShowADirection) {
  GnssHeadingOffset heading;
  // Slower than 2.5 sd of the fix's noise, slower than 0.3 m/s, wheels still, a NaN.
  EXPECT_FALSE(heading.Observe(0.4, 0.0, 0.3, 0.0, 5.0));
  EXPECT_FALSE(heading.Observe(0.2, 0.0, 0.01, 0.0, 5.0));
  EXPECT_FALSE(heading.Observe(1.0, 0.0, 0.1, 0.0, 0.1));
  EXPECT_FALSE(heading.Observe(1.0, 0.0, 0.1, std::nan(""), 5.0));
  EXPECT_EQ(heading.fixes_counted(), 0);
  EXPECT_EQ(heading.mean_rad(), 0.0);
  EXPECT_TRUE(heading.Observe(1.0, 0.0, 0.1, 0.0, 5.0));
}

TEST(GnssHeadingOffset, FollowsAnOffsetThatChanges) {
  // The yaw's reference moves from +0.3 to -0.3 rad (an AHRS near steel): after 3 spans of the
  // average the offset is the new one.
  GnssHeadingOffset heading;
  for (int i = 0; i < 120; ++i) {
    const double offset = i < 60 ? 0.3 : -0.3;
    heading.Observe(std::cos(offset), std::sin(offset), 0.1, 0.0, 5.0);
  }
  EXPECT_NEAR(heading.offset_rad(), -0.3, 0.01);
}

}  // namespace
}  // namespace slipgraph
