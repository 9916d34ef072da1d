#include "factors/traction.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/jacobian_check.h"

namespace slipgraph {
namespace {

const TireParams kTire{0.8, 20.0, 0.05};

TEST(Traction, HandComputedPoint) {
  // 500 (0.8 (1 - exp(-20 * 0.1)) + 0.05 * 0.1) = 348.3658867...
  EXPECT_NEAR(TractionForceN(500.0, 0.1, kTire), 348.36588670535497, 1e-9);
  EXPECT_NEAR(TractionForceN(500.0, -0.1, kTire), -348.36588670535497, 1e-9);  // braking
  EXPECT_EQ(TractionForceN(500.0, 0.0, kTire), 0.0);
}

TEST(Traction, AFallingBranchReversesWhereC1IsOutweighed) {
  // C1 0.29, At 200 (saturated within a few cm/s), C2 -0.5: 0.29 (1 - exp(-200 v)) = 0.5 v at
  // v = 0.58 m/s.
  TireParams tire{0.29, 200.0, -0.5};
  const double v = TractionReversalSpeedMps(tire, 1.35);
  EXPECT_NEAR(v, 0.58, 1e-3);
  EXPECT_NEAR(TractionForceN(1.0, v, tire), 0.0, 1e-9);
  EXPECT_TRUE(std::isnan(TractionReversalSpeedMps(tire, 0.5)));  // not within 0.5 m/s
  tire.C2 = 0.05;
  EXPECT_TRUE(std::isnan(TractionReversalSpeedMps(tire, 100.0)));  // no falling branch
  tire = {0.3, 20.0, -0.1};                                        // 3 m/s
  EXPECT_NEAR(TractionReversalSpeedMps(tire, 10.0), 0.3 * (1.0 - std::exp(-20.0 * 3.0)) / 0.1,
              1e-6);
}

TEST(Traction, RelativeVelocity) { EXPECT_DOUBLE_EQ(TireRelativeVelocityMps(4.0, 0.25, 0.8), 0.2); }

// f(N, v_rel) -> F, for Jacobian checks in both inputs.
struct TractionFn {
  template <typename T>
  void operator()(const T* x, T* y) const {
    y[0] = TractionForceN(x[0], x[1], kTire);
  }
};

TEST(Traction, JacobianMatchesCentralDifferencesIncludingZeroRelativeVelocity) {
  for (double v_rel : {-1.0, -0.05, -1e-6, 0.0, 1e-6, 0.05, 1.0}) {
    const double x[2] = {500.0, v_rel};
    const auto ad = testing::AutoDiffJacobian<2, 1>(TractionFn(), x);
    const auto nd = testing::CentralDifferenceJacobian<2, 1>(TractionFn(), x);
    EXPECT_LT(testing::MaxRelativeDifference(ad, nd), 1e-5) << "v_rel=" << v_rel;
  }
  // At v_rel = 0 the slope is N (C1 At + C2) = 500 (16 + 0.05).
  const double x0[2] = {500.0, 0.0};
  EXPECT_NEAR((testing::AutoDiffJacobian<2, 1>(TractionFn(), x0)(0, 1)), 8025.0, 1e-9);
}

}  // namespace
}  // namespace slipgraph
