// REP-103 to Ward's angles: the pitch changes sign (nose down to uphill), the roll keeps it; a
// robot climbing a hill pitches nose up, so its REP-103 pitch is negative and Ward's phi positive.
// A GNSS velocity along the body's x axis, with and without an attitude.
#include "factors/frames.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>

namespace slipgraph {
namespace {

TEST(Frames, PitchChangesSignRollKeepsIt) {
  EXPECT_EQ(WardPitchUphillRad(-0.1), 0.1);
  EXPECT_EQ(WardPitchUphillRad(0.2), -0.2);
  EXPECT_EQ(WardRollRad(0.05), 0.05);
  const ceres::Jet<double, 1> pitch(0.3, 0);
  EXPECT_EQ(WardPitchUphillRad(pitch).v[0], -1.0);  // and its derivative
}

TEST(Frames, GnssVelocityAlongBodyX) {
  // Heading north-east (yaw 45 deg) on the flat at 1 m/s: all of it along x.
  const double c = std::sqrt(0.5);
  EXPECT_NEAR(GnssVelocityAlongBodyX(c, c, 0.0, true, 0.0, M_PI / 4, 0.0), 1.0, 1e-15);
  // Heading east, the velocity north: nothing along x.
  EXPECT_NEAR(GnssVelocityAlongBodyX(0.0, 1.0, 0.0, true, 0.0, 0.0, 0.0), 0.0, 1e-15);
  // Climbing at 0.1 rad (REP-103 pitch -0.1, nose up) along the path: the path's speed.
  const double up = 0.1;
  EXPECT_NEAR(GnssVelocityAlongBodyX(std::cos(up), 0.0, std::sin(up), true, -up, 0.0, 0.0), 1.0,
              1e-15);
  // Driving backwards east while facing east: negative.
  EXPECT_NEAR(GnssVelocityAlongBodyX(-0.5, 0.0, 0.0, true, 0.0, 0.0, 0.0), -0.5, 1e-15);
  // No attitude: the horizontal speed, signed by the wheels (forward at a sum of 0).
  EXPECT_DOUBLE_EQ(GnssVelocityAlongBodyX(0.3, 0.4, 9.0, false, 0.0, 0.0, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(GnssVelocityAlongBodyX(0.3, 0.4, 9.0, false, 0.0, 0.0, -2.0), -0.5);
  EXPECT_DOUBLE_EQ(GnssVelocityAlongBodyX(0.3, 0.4, 9.0, false, 0.0, 0.0, 0.0), 0.5);
}

}  // namespace
}  // namespace slipgraph
