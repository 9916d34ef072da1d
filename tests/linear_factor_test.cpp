// The linear factor r = sum_b A_b x_b - rhs over blocks of different sizes: residual by hand, the
// hand-written (constant) Jacobian against numeric differentiation, and a block whose Jacobian is
// not asked for.
#include "factors/linear_factor.h"

#include <gtest/gtest.h>

#include "tests/factor_check.h"

namespace slipgraph {
namespace {

LinearFactor TwoBlocks() {
  LinearFactor::Matrix a0(3, 2), a1(3, 4);
  a0 << 1.0, -2.0, 0.5, 0.0, 3.0, 1.5;
  a1 << 0.0, 1.0, -1.0, 2.0, 4.0, 0.0, 0.25, -0.5, 1.0, 1.0, 1.0, -3.0;
  Eigen::VectorXd rhs(3);
  rhs << 0.1, -0.2, 0.3;
  return LinearFactor({a0, a1}, rhs);
}

TEST(LinearFactor, ResidualByHand) {
  const LinearFactor f = TwoBlocks();
  ASSERT_EQ(f.num_residuals(), 3);
  ASSERT_EQ(f.parameter_block_sizes(), (std::vector<int32_t>{2, 4}));
  const double x0[] = {1.0, 2.0};
  const double x1[] = {-1.0, 0.5, 2.0, 1.0};
  const std::vector<double> r = testing::Residuals(f, {x0, x1});
  EXPECT_NEAR(r[0], (1.0 - 4.0) + (0.5 - 2.0 + 2.0) - 0.1, 1e-12);
  EXPECT_NEAR(r[1], 0.5 + (-4.0 + 0.5 - 0.5) + 0.2, 1e-12);
  EXPECT_NEAR(r[2], (3.0 + 3.0) + (-1.0 + 0.5 + 2.0 - 3.0) - 0.3, 1e-12);
}

TEST(LinearFactor, JacobiansMatchNumericDifferentiation) {
  const LinearFactor f = TwoBlocks();
  const double x0[] = {0.3, -0.7};
  const double x1[] = {2.0, -1.5, 0.25, 4.0};
  testing::ExpectJacobiansMatchNumeric(f, {x0, x1});
}

TEST(LinearFactor, OnlyTheAskedJacobianIsWritten) {
  const LinearFactor f = TwoBlocks();
  const double x0[] = {0.3, -0.7};
  const double x1[] = {2.0, -1.5, 0.25, 4.0};
  const double* parameters[] = {x0, x1};
  double residuals[3];
  double j1[12];
  double* jacobians[] = {nullptr, j1};
  ASSERT_TRUE(f.Evaluate(parameters, residuals, jacobians));
  EXPECT_EQ(j1[1], 1.0);
  EXPECT_EQ(j1[11], -3.0);
}

}  // namespace
}  // namespace slipgraph
