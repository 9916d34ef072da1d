// The attitude's yaw against the GNSS course: an offset found from noisy fixes, driving forwards
// or backwards, across +-pi, with an sd that matches its scatter; left at zero where the yaw
// agrees within noise or the mean is within 3 sd of zero, before enough fixes, and from fixes
// too slow, in a turn or with the wheels still; outliers left out, a moved reference followed.
#include "factors/gnss_heading_offset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

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
    heading.Observe(ve, vn, sd_v, yaw, speed, 0.0);
  }
  return heading;
}

// One fix at 1 m/s whose course is `d` from a yaw of 0, straight ahead.
bool ObserveAt(GnssHeadingOffset* heading, double d) {
  return heading->Observe(std::cos(d), std::sin(d), 0.1, 0.0, 1.0, 0.0);
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

TEST(GnssHeadingOffset, FindsAnOffsetAcrossPi) {
  // Course minus yaw near +-pi: the fixes' differences wrap from +3.1 to -3.1.
  for (uint64_t seed : {1, 2, 3}) {
    const GnssHeadingOffset heading = Drive(3.0, 1.0, 0.15, 80, seed);
    EXPECT_NEAR(std::remainder(heading.offset_rad() - 3.0, 2.0 * M_PI), 0.0, 0.08) << seed;
    EXPECT_LT(heading.sd_rad(), 0.06) << seed;
  }
}

TEST(GnssHeadingOffset, LeavesAYawThatAgreesWithinNoise) {
  for (uint64_t seed : {1, 2, 3, 4, 5}) {
    const GnssHeadingOffset heading = Drive(0.01, 1.0, 0.1, 200, seed);
    EXPECT_NEAR(heading.mean_rad(), 0.01, 0.06);
    EXPECT_EQ(heading.offset_rad(), 0.0) << seed;
  }
}

TEST(GnssHeadingOffset, LeavesAMeanWithin3SdOfZero) {
  // Fixes 0.3 rad either side of 0.08: a mean beyond min_offset_rad (0.05) but within 3 sd
  // (0.3 / sqrt(19) = 0.069) of zero is not applied; 0.03 either side of it is.
  GnssHeadingOffset scattered, tight;
  for (int i = 0; i < 60; ++i) {
    ObserveAt(&scattered, 0.08 + (i % 2 == 0 ? 0.3 : -0.3));
    ObserveAt(&tight, 0.08 + (i % 2 == 0 ? 0.03 : -0.03));
  }
  EXPECT_GT(scattered.mean_rad(), 0.05);
  EXPECT_GT(3.0 * scattered.sd_rad(), scattered.mean_rad());
  EXPECT_EQ(scattered.offset_rad(), 0.0);
  EXPECT_NEAR(tight.offset_rad(), 0.08, 0.005);
}

TEST(GnssHeadingOffset, ItsSdIsTheScatterOfItsMean) {
  // Course minus yaw drawn with sd 0.1 rad: across 400 drives, the stated sd at the end matches
  // how far the mean is from the truth (0.1 / sqrt(20) = 0.022 for an average over 20 fixes).
  std::mt19937_64 rng(7);
  std::normal_distribution<double> angle(0.0, 0.1);
  double error_sq = 0.0, stated_sq = 0.0;
  const int drives = 400;
  for (int drive = 0; drive < drives; ++drive) {
    GnssHeadingOffset heading;
    for (int i = 0; i < 100; ++i) {
      const double d = 0.3 + angle(rng);  // stated 0.01 m/s at 1 m/s: the scatter sets the sd
      heading.Observe(std::cos(d), std::sin(d), 0.01, 0.0, 1.0, 0.0);
    }
    error_sq += std::pow(heading.mean_rad() - 0.3, 2) / drives;
    stated_sq += std::pow(heading.sd_rad(), 2) / drives;
  }
  EXPECT_NEAR(std::sqrt(error_sq), 0.1 / std::sqrt(20.0), 0.003);
  EXPECT_NEAR(std::sqrt(stated_sq) / std::sqrt(error_sq), 1.0, 0.15);
}

TEST(GnssHeadingOffset, WaitsForEnoughFixes) {
  EXPECT_EQ(Drive(0.5, 1.0, 0.05, 4, 1).offset_rad(), 0.0);
  EXPECT_NEAR(Drive(0.5, 1.0, 0.05, 5, 1).offset_rad(), 0.5, 0.1);
}

TEST(GnssHeadingOffset, CountsOnlyFixesThatShowADirection) {
  GnssHeadingOffset heading;
  // Slower than 2.5 sd of the fix's noise, slower than 0.3 m/s, wheels still, a turn of radius
  // 2 m (its sideslip and the antenna's lever arm move the course off the heading), a NaN.
  EXPECT_FALSE(heading.Observe(0.4, 0.0, 0.3, 0.0, 1.0, 0.0));
  EXPECT_FALSE(heading.Observe(0.2, 0.0, 0.01, 0.0, 1.0, 0.0));
  EXPECT_FALSE(heading.Observe(1.0, 0.0, 0.1, 0.0, 0.02, 0.0));
  EXPECT_FALSE(heading.Observe(1.0, 0.0, 0.1, 0.0, 1.0, 0.5));
  EXPECT_FALSE(heading.Observe(1.0, 0.0, 0.1, std::nan(""), 1.0, 0.0));
  EXPECT_EQ(heading.fixes_counted(), 0);
  EXPECT_EQ(heading.mean_rad(), 0.0);
  EXPECT_TRUE(heading.Observe(1.0, 0.0, 0.1, 0.0, 1.0, 0.1));  // radius 10 m
  GnssHeadingOffset backwards;                                 // the course minus pi is the heading
  EXPECT_TRUE(backwards.Observe(-1.0, 0.0, 0.1, 0.0, -1.0, 0.0));
  EXPECT_NEAR(backwards.mean_rad(), 0.0, 1e-12);
}

TEST(GnssHeadingOffset, LeavesOutAFixFarFromAnEstablishedMean) {
  GnssHeadingOffset heading;
  for (int i = 0; i < 10; ++i) ObserveAt(&heading, 0.3);
  EXPECT_FALSE(ObserveAt(&heading, 0.3 + 2.0));  // a multipath fix
  EXPECT_NEAR(heading.offset_rad(), 0.3, 1e-12);
  EXPECT_TRUE(ObserveAt(&heading, 0.3 + 1.0));  // within pi/2: counted
}

TEST(GnssHeadingOffset, FollowsAnOffsetThatChanges) {
  // The yaw's reference moves from +0.3 to -0.3 rad (an AHRS near steel): after 3 spans of the
  // average the offset is the new one. A jump beyond pi/2 (a yaw that flipped) restarts the
  // average after min_fixes outliers in a row.
  GnssHeadingOffset heading;
  for (int i = 0; i < 120; ++i) ObserveAt(&heading, i < 60 ? 0.3 : -0.3);
  EXPECT_NEAR(heading.offset_rad(), -0.3, 0.01);
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(ObserveAt(&heading, 2.5));
  EXPECT_TRUE(ObserveAt(&heading, 2.5));
  EXPECT_EQ(heading.fixes_counted(), 1);
  for (int i = 0; i < 4; ++i) ObserveAt(&heading, 2.5);
  EXPECT_NEAR(heading.offset_rad(), 2.5, 1e-12);
}

TEST(GnssHeadingOffsetOptions, NamesAFieldOutOfRange) {
  std::string error;
  EXPECT_TRUE(GnssHeadingOffsetOptions{}.IsValid(&error));
  GnssHeadingOffsetOptions options;
  options.min_fixes = 0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("min_fixes"), std::string::npos) << error;
  options = {};
  options.fixes = 0.5;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("fixes"), std::string::npos) << error;
}

}  // namespace
}  // namespace slipgraph
