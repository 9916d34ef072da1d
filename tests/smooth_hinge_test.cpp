// The smooth one-sided penalties of the soft priors: close to max(u, 0) and |u| away from zero,
// their stated value at zero, and derivatives finite everywhere (checked against central
// differences, and by automatic differentiation at the kink).
#include "factors/smooth_hinge.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/jacobian_check.h"

namespace slipgraph {
namespace {

constexpr double kEps = 0.01;

TEST(SmoothHinge, ApproachesTheHingeAwayFromZero) {
  EXPECT_NEAR(SmoothHinge(1.0, kEps), 1.0, kEps * kEps);
  EXPECT_NEAR(SmoothHinge(-1.0, kEps), 0.0, kEps * kEps);
  EXPECT_DOUBLE_EQ(SmoothHinge(0.0, kEps), kEps / 2.0);
  for (double u = -0.5; u <= 0.5; u += 0.01) {
    EXPECT_GE(SmoothHinge(u, kEps), std::max(u, 0.0)) << u;
    EXPECT_LE(SmoothHinge(u, kEps), std::max(u, 0.0) + kEps / 2.0 + 1e-15) << u;
  }
}

TEST(SmoothHinge, AbsoluteApproachesTheAbsoluteValue) {
  EXPECT_DOUBLE_EQ(SmoothAbsolute(0.0, kEps), 0.0);
  EXPECT_NEAR(SmoothAbsolute(-2.0, kEps), 2.0 - kEps, kEps * kEps);
  EXPECT_NEAR(SmoothAbsolute(2.0, kEps), 2.0 - kEps, kEps * kEps);
}

TEST(SmoothHinge, DerivativesFiniteAndMatchCentralDifferences) {
  const auto both = [](const auto* u, auto* y) {
    y[0] = SmoothHinge(u[0], kEps);
    y[1] = SmoothAbsolute(u[0], kEps);
  };
  for (double u : {-0.3, -kEps, 0.0, 0.5 * kEps, 0.2}) {
    const auto autodiff = testing::AutoDiffJacobian<1, 2>(both, &u);
    const auto numeric = testing::CentralDifferenceJacobian<1, 2>(both, &u, 1e-7);
    EXPECT_TRUE(autodiff.allFinite()) << u;
    EXPECT_NEAR(autodiff(0, 0), numeric(0, 0), 1e-6) << u;
    EXPECT_NEAR(autodiff(1, 0), numeric(1, 0), 1e-6) << u;
  }
  // At the kink: a half slope for the hinge, zero for the absolute value.
  const double zero = 0.0;
  const auto at_zero = testing::AutoDiffJacobian<1, 2>(both, &zero);
  EXPECT_DOUBLE_EQ(at_zero(0, 0), 0.5);
  EXPECT_DOUBLE_EQ(at_zero(1, 0), 0.0);
}

}  // namespace
}  // namespace slipgraph
