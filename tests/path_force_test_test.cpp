// The omnibus chi-square of scores with a rank-deficient Gram matrix.
#include "workbench/path_force_test.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

namespace slipgraph {
namespace {

TEST(PathForceTest, ChiSquareUsesThePseudoInverseAndItsRank) {
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(3, 3);
  gram(0, 0) = 4.0, gram(1, 1) = 1.0;  // the third direction carries no information
  const Eigen::Vector3d score(2.0, 3.0, 5.0);
  const auto [x2, rank] = ChiSquareOfScores(score, gram);
  EXPECT_EQ(rank, 2);
  EXPECT_NEAR(x2, 4.0 / 4.0 + 9.0 / 1.0, 1e-12);
}

TEST(PathForceTest, ChiSquareIsInvariantToARotationOfTheBasis) {
  Eigen::Matrix2d gram;
  gram << 2.0, 0.5, 0.5, 1.0;
  const Eigen::Vector2d score(1.0, -2.0);
  const double direct = score.dot(gram.inverse() * score);
  Eigen::Matrix2d rotation;
  rotation << std::cos(0.3), -std::sin(0.3), std::sin(0.3), std::cos(0.3);
  const auto [x2, rank] =
      ChiSquareOfScores(rotation * score, rotation * gram * rotation.transpose());
  EXPECT_EQ(rank, 2);
  EXPECT_NEAR(x2, direct, 1e-12);
}

TEST(PathForceTest, NothingToTestWithoutAGraph) {
  ModelResiduals m;
  EXPECT_FALSE(TestForceAlongPath(m, nullptr, "", 0.05).tested);
}

}  // namespace
}  // namespace slipgraph
