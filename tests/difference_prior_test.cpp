// The prior on the step between two blocks: residual by hand, Jacobians against numeric
// differentiation, for the Wilcox advance (N = 1) and the IPD slip-model walk (N = 13).
#include "factors/difference_prior.h"

#include <gtest/gtest.h>

#include <memory>

#include "factors/ipd_segment.h"
#include "tests/factor_check.h"

namespace slipgraph {
namespace {

TEST(DifferencePrior, AdvanceResidualByHandAndJacobians) {
  std::unique_ptr<ceres::CostFunction> cost(DifferencePrior<1>::Create({0.25}, 0.02));
  const double a = 1.0, b = 1.3;
  const std::vector<double> r = testing::Residuals(*cost, {&a, &b});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_NEAR(r[0], (1.3 - 1.0 - 0.25) / 0.02, 1e-12);
  testing::ExpectJacobiansMatchNumeric(*cost, {&a, &b});
}

TEST(DifferencePrior, SlipModelWalkPerComponentAndJacobians) {
  constexpr int N = ipd::kAlphaSize;
  std::unique_ptr<ceres::CostFunction> cost(DifferencePrior<N>::Create({}, 0.5));
  std::array<double, N> a{}, b{};
  for (int i = 0; i < N; ++i) {
    a[i] = 0.1 * i - 0.4;
    b[i] = 0.3 - 0.07 * i * i;
  }
  const std::vector<double> r = testing::Residuals(*cost, {a.data(), b.data()});
  ASSERT_EQ(r.size(), static_cast<size_t>(N));
  for (int i = 0; i < N; ++i) EXPECT_NEAR(r[i], (b[i] - a[i]) / 0.5, 1e-12) << i;
  testing::ExpectJacobiansMatchNumeric(*cost, {a.data(), b.data()});
}

}  // namespace
}  // namespace slipgraph
