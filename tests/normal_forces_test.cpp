#include "factors/normal_forces.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/jacobian_check.h"

namespace slipgraph {
namespace {

// LAGR-like geometry: a = 0.35, b = 0.55, c = 0.55, h = 0.3, 117 kg.
constexpr double kA = 0.35, kB = 0.55, kC = 0.55, kH = 0.3;
const double kWeight = 117.0 * 9.80665;

TEST(NormalForces, FlatGroundSplitsByAxleDistances) {
  const auto n = DiffDriveCastorNormalForcesN(kWeight, 0.0, 0.0, kA, kB, kC, kH);
  EXPECT_NEAR(n.front_left_n, kWeight / 2 * kB / (kA + kB), 1e-9);  // 350.5877 N
  EXPECT_NEAR(n.front_right_n, 350.58773750000006, 1e-9);
  EXPECT_NEAR(n.rear_each_n, 223.10128749999998, 1e-9);
}

TEST(NormalForces, HandComputedRolledAndPitched) {
  // roll 0.1 rad (right side down), uphill pitch 0.2 rad; values from eqs. (3)-(5).
  const auto n = DiffDriveCastorNormalForcesN(kWeight, 0.1, 0.2, kA, kB, kC, kH);
  EXPECT_NEAR(n.front_left_n, 242.6567250747006, 1e-9);
  EXPECT_NEAR(n.front_right_n, 365.12584918612396, 1e-9);
  EXPECT_NEAR(n.rear_each_n, 255.55322709092843, 1e-9);
  // The loads carry the weight's component normal to the ground.
  EXPECT_NEAR(n.front_left_n + n.front_right_n + 2 * n.rear_each_n,
              kWeight * std::cos(0.2) * std::cos(0.1), 1e-9);
}

TEST(NormalForces, SideTotalsEqualDiffDriveSideSums) {
  const auto n = DiffDriveCastorNormalForcesN(kWeight, 0.1, 0.2, kA, kB, kC, kH);
  const auto side = SideTotalNormalForcesN(kWeight, 0.1, 0.2, kC, kH);
  EXPECT_NEAR(side.left_n, n.front_left_n + n.rear_each_n, 1e-9);
  EXPECT_NEAR(side.right_n, n.front_right_n + n.rear_each_n, 1e-9);
}

struct NormalFn {
  template <typename T>
  void operator()(const T* x, T* y) const {
    const auto n = DiffDriveCastorNormalForcesN(kWeight, x[0], x[1], kA, kB, kC, kH);
    y[0] = n.front_left_n, y[1] = n.front_right_n, y[2] = n.rear_each_n;
  }
};

TEST(NormalForces, JacobianMatchesCentralDifferences) {
  for (const auto& angles : {std::array<double, 2>{0.0, 0.0}, {0.1, -0.3}, {-0.2, 0.25}}) {
    const auto ad = testing::AutoDiffJacobian<2, 3>(NormalFn(), angles.data());
    const auto nd = testing::CentralDifferenceJacobian<2, 3>(NormalFn(), angles.data());
    EXPECT_LT(testing::MaxRelativeDifference(ad, nd), 1e-6);
  }
}

}  // namespace
}  // namespace slipgraph
