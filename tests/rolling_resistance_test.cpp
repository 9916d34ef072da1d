#include "factors/rolling_resistance.h"

#include <gtest/gtest.h>

#include "tests/jacobian_check.h"

namespace slipgraph {
namespace {

const RollingParams kRolling{0.03, 20.0, 0.01};

TEST(RollingResistance, HandComputedPoint) {
  // -500 (0.03 (1 - exp(-10)) + 0.01 * 0.5) = -17.4993190...
  EXPECT_NEAR(RollingResistanceForceN(500.0, 0.5, kRolling), -17.499319001053564, 1e-9);
  EXPECT_NEAR(RollingResistanceForceN(500.0, -0.5, kRolling), 17.499319001053564, 1e-9);
  EXPECT_EQ(RollingResistanceForceN(500.0, 0.0, kRolling), 0.0);
}

struct RollingFn {
  template <typename T>
  void operator()(const T* x, T* y) const {
    y[0] = RollingResistanceForceN(x[0], x[1], kRolling);
  }
};

TEST(RollingResistance, JacobianMatchesCentralDifferencesIncludingZeroSpeed) {
  for (double v : {-2.0, -0.01, 0.0, 1e-7, 0.01, 2.0}) {
    const double x[2] = {400.0, v};
    const auto ad = testing::AutoDiffJacobian<2, 1>(RollingFn(), x);
    const auto nd = testing::CentralDifferenceJacobian<2, 1>(RollingFn(), x);
    EXPECT_LT(testing::MaxRelativeDifference(ad, nd), 1e-5) << "v=" << v;
  }
  // Slope at v = 0: -N (R1 A_roll + R2) = -500 (0.6 + 0.01).
  const double x0[2] = {500.0, 0.0};
  EXPECT_NEAR((testing::AutoDiffJacobian<2, 1>(RollingFn(), x0)(0, 1)), -305.0, 1e-9);
}

}  // namespace
}  // namespace slipgraph
