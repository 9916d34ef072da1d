#include "factors/smooth_math.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>

namespace slipgraph {
namespace {

using Jet1 = ceres::Jet<double, 1>;

double Literal(double v, double rate) {
  const double sign = v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
  return sign * (1.0 - std::exp(-rate * std::abs(v)));
}

TEST(SmoothMath, MatchesLiteralFormulaAwayFromZeroAndInTaylorBranch) {
  for (double v : {-3.0, -0.2, -1e-5, -1e-7, 1e-9, 1e-6, 4e-5, 0.01, 0.3, 2.0}) {
    EXPECT_NEAR(SignedSaturation(v, 20.0), Literal(v, 20.0), 1e-14) << "v=" << v;
  }
  EXPECT_EQ(SignedSaturation(0.0, 20.0), 0.0);
}

TEST(SmoothMath, JetDerivativeAtExactlyZeroIsTheRate) {
  // The literal sign(v)(1 - exp(-A|v|)) gives a zero Jet derivative here; the true slope is A.
  const Jet1 y = SignedSaturation(Jet1(0.0, 0), 20.0);
  EXPECT_EQ(y.a, 0.0);
  EXPECT_DOUBLE_EQ(y.v[0], 20.0);
}

TEST(SmoothMath, JetDerivativeMatchesCentralDifferenceAcrossBranches) {
  const double rate = 20.0;
  // Both sides of the Taylor switch at rate |v| = 1e-3, i.e. |v| = 5e-5.
  for (double v : {-0.5, -5.1e-5, -4.9e-5, -1e-8, 0.0, 1e-8, 4.9e-5, 5.1e-5, 0.5}) {
    const double h = 1e-7;
    const double numeric =
        (SignedSaturation(v + h, rate) - SignedSaturation(v - h, rate)) / (2.0 * h);
    const Jet1 y = SignedSaturation(Jet1(v, 0), rate);
    EXPECT_NEAR(y.v[0], numeric, 1e-6 * rate) << "v=" << v;
    EXPECT_NEAR(y.v[0], rate * std::exp(-rate * std::abs(v)), 1e-9 * rate) << "v=" << v;
  }
}

}  // namespace
}  // namespace slipgraph
