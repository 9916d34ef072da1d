// REP-103 to Ward's angles: the pitch changes sign (nose down to uphill), the roll keeps it; a
// robot climbing a hill pitches nose up, so its REP-103 pitch is negative and Ward's phi positive.
#include "factors/frames.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

namespace slipgraph {
namespace {

TEST(Frames, PitchChangesSignRollKeepsIt) {
  EXPECT_EQ(WardPitchUphillRad(-0.1), 0.1);
  EXPECT_EQ(WardPitchUphillRad(0.2), -0.2);
  EXPECT_EQ(WardRollRad(0.05), 0.05);
  const ceres::Jet<double, 1> pitch(0.3, 0);
  EXPECT_EQ(WardPitchUphillRad(pitch).v[0], -1.0);  // and its derivative
}

}  // namespace
}  // namespace slipgraph
