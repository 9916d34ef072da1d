// MarginalPrior: the linear residual that reproduces a Hessian and gradient on its blocks.
#include "factors/marginal_prior.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "tests/factor_check.h"

namespace slipgraph {
namespace {

TEST(MarginalPrior, ReproducesHessianAndGradientAtTheLinearizationPoint) {
  Eigen::MatrixXd H(3, 3);
  H << 4.0, 1.0, 0.5,  //
      1.0, 3.0, 0.2,   //
      0.5, 0.2, 2.0;
  const Eigen::VectorXd b = Eigen::Vector3d(0.3, -1.0, 2.0);
  const Eigen::VectorXd x0 = Eigen::Vector3d(1.0, 2.0, -1.0);
  const MarginalPrior prior({2, 1}, x0, H, b);
  EXPECT_EQ(prior.rank(), 3);
  const double a[2] = {1.0, 2.0};
  const double c[1] = {-1.0};
  const double* parameters[2] = {a, c};
  Eigen::VectorXd r(prior.num_residuals());
  Eigen::Matrix<double, 3, 2, Eigen::RowMajor> Ja;
  Eigen::Matrix<double, 3, 1> Jc;
  double* jacobians[2] = {Ja.data(), Jc.data()};
  ASSERT_TRUE(prior.Evaluate(parameters, r.data(), jacobians));
  Eigen::MatrixXd J(3, 3);
  J << Ja, Jc;
  EXPECT_TRUE((J.transpose() * J).isApprox(H, 1e-12));
  EXPECT_TRUE((J.transpose() * r).isApprox(b, 1e-12));
  testing::ExpectJacobiansMatchNumeric(prior, {a, c});
}

TEST(MarginalPrior, IsLinearAwayFromTheLinearizationPoint) {
  const Eigen::MatrixXd H = Eigen::Vector2d(4.0, 9.0).asDiagonal();
  const Eigen::VectorXd b = Eigen::Vector2d::Zero();
  const MarginalPrior prior({2}, Eigen::Vector2d(1.0, 1.0), H, b);
  // By hand: r = diag(2, 3) (x - x0) up to the order and signs of the eigenvectors.
  const double x[2] = {2.0, 0.0};
  const std::vector<double> r = testing::Residuals(prior, {x});
  EXPECT_NEAR(0.5 * (r[0] * r[0] + r[1] * r[1]), 0.5 * (4.0 * 1.0 + 9.0 * 1.0), 1e-12);
  testing::ExpectJacobiansMatchNumeric(prior, {x});
}

TEST(MarginalPrior, DropsDirectionsWithoutInformation) {
  Eigen::MatrixXd H(2, 2);
  H << 1.0, 1.0,  //
      1.0, 1.0;   // rank one: only x1 + x2 is known
  const MarginalPrior prior({2}, Eigen::Vector2d::Zero(), H, Eigen::Vector2d(1.0, 1.0));
  EXPECT_EQ(prior.rank(), 1);
  EXPECT_EQ(prior.num_residuals(), 1);
  const double along_null[2] = {1.0, -1.0};
  const double zero[2] = {0.0, 0.0};
  EXPECT_NEAR(testing::Residuals(prior, {along_null})[0], testing::Residuals(prior, {zero})[0],
              1e-12);
}

// The Cholesky path is taken only where the eigen-decomposition would keep every direction: a
// direction 1e-14 of the largest is declined (the caller drops it), one 1e-6 of it is inverted.
TEST(MarginalPrior, FullRankInverseDeclinesWhatTheEigenFloorWouldDrop) {
  Eigen::LLT<Eigen::MatrixXd> llt;
  Eigen::MatrixXd inverse;
  const Eigen::MatrixXd rotation = Eigen::Rotation2Dd(0.3).toRotationMatrix();
  const Eigen::MatrixXd tiny =
      rotation * Eigen::Vector2d(1.0, 1e-14).asDiagonal() * rotation.transpose();
  EXPECT_FALSE(FullRankInverse(tiny, 1e-12, &llt, &inverse));
  const Eigen::MatrixXd small =
      rotation * Eigen::Vector2d(1.0, 1e-6).asDiagonal() * rotation.transpose();
  ASSERT_TRUE(FullRankInverse(small, 1e-12, &llt, &inverse));
  EXPECT_TRUE((inverse * small).isApprox(Eigen::Matrix2d::Identity(), 1e-8));
  // The prior from it: the same Hessian and gradient as the eigen-decomposition's.
  const Eigen::VectorXd b = Eigen::Vector2d(0.4, -0.2);
  const MarginalPrior prior({2}, Eigen::Vector2d::Zero(), small, b);
  EXPECT_EQ(prior.rank(), 2);
  const double at[2] = {0.0, 0.0};
  Eigen::Vector2d r;
  Eigen::Matrix<double, 2, 2, Eigen::RowMajor> J;
  double* jacobians[1] = {J.data()};
  const double* parameters[1] = {at};
  ASSERT_TRUE(prior.Evaluate(parameters, r.data(), jacobians));
  EXPECT_TRUE((J.transpose() * J).isApprox(small, 1e-10));
  EXPECT_TRUE((J.transpose() * r).isApprox(b, 1e-10));
}

}  // namespace
}  // namespace slipgraph
