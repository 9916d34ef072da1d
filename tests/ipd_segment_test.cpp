// IPD over a path segment: prediction by hand, its Jacobian in alpha, the covariance terms of
// eq. (15) by hand, and the relative pose of eq. (12).
#include "factors/ipd_segment.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace slipgraph {
namespace {

using ipd::OdometryStep;

std::vector<OdometryStep> Straight(double v, double seconds, double dt = 0.01) {
  return std::vector<OdometryStep>(static_cast<size_t>(std::round(seconds / dt)),
                                   OdometryStep{dt, v, 0.0, 0.0, 0.0});
}

TEST(IpdSegment, NoSlipStraightLineByHand) {
  const std::array<double, ipd::kAlphaSize> alpha{};
  double pose[3];
  ipd::PredictSegment(Straight(1.0, 2.0), alpha.data(), 9.81, pose);
  EXPECT_NEAR(pose[0], 2.0, 1e-12);
  EXPECT_NEAR(pose[1], 0.0, 1e-12);
  EXPECT_NEAR(pose[2], 0.0, 1e-12);
}

TEST(IpdSegment, ForwardSlipShortensTheAdvance) {
  std::array<double, ipd::kAlphaSize> alpha{};
  alpha[0] = -0.1;  // V_s,x = -0.1 V_x
  double pose[3];
  ipd::PredictSegment(Straight(1.0, 2.0), alpha.data(), 9.81, pose);
  EXPECT_NEAR(pose[0], 1.8, 1e-12);
}

TEST(IpdSegment, TurningInPlaceByHand) {
  // Tracks saying 1 rad/s for 1 s, yaw slip gain alpha[9] = -0.2: 0.8 rad, no translation.
  std::array<double, ipd::kAlphaSize> alpha{};
  alpha[9] = -0.2;
  std::vector<OdometryStep> steps(100, OdometryStep{0.01, 0.0, 1.0, 0.0, 0.0});
  double pose[3];
  ipd::PredictSegment(steps, alpha.data(), 9.81, pose);
  EXPECT_NEAR(pose[2], 0.8, 1e-9);
  EXPECT_NEAR(std::hypot(pose[0], pose[1]), 0.0, 1e-12);
}

TEST(IpdSegment, AlphaJacobianMatchesCentralDifferences) {
  std::vector<OdometryStep> steps;
  for (int k = 0; k < 200; ++k) {
    steps.push_back({0.01, 0.8 + 0.3 * std::sin(0.05 * k), 0.5 * std::cos(0.03 * k),
                     0.05 * std::sin(0.02 * k), -0.08 + 0.001 * k});
  }
  std::array<double, ipd::kAlphaSize> alpha;
  for (int i = 0; i < ipd::kAlphaSize; ++i) alpha[i] = 0.01 * (i - 6);
  using Jet = ceres::Jet<double, ipd::kAlphaSize>;
  std::array<Jet, ipd::kAlphaSize> alpha_jet;
  for (int i = 0; i < ipd::kAlphaSize; ++i) alpha_jet[i] = Jet(alpha[i], i);
  Jet pose_jet[3];
  ipd::PredictSegment(steps, alpha_jet.data(), 9.81, pose_jet);
  for (int i = 0; i < ipd::kAlphaSize; ++i) {
    const double h = 1e-6;
    auto plus = alpha, minus = alpha;
    plus[i] += h;
    minus[i] -= h;
    double p[3], m[3];
    ipd::PredictSegment(steps, plus.data(), 9.81, p);
    ipd::PredictSegment(steps, minus.data(), 9.81, m);
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(pose_jet[r].v[i], (p[r] - m[r]) / (2.0 * h), 1e-6)
          << "row " << r << " alpha " << i;
    }
  }
}

TEST(IpdSegment, CovarianceTermsByHand) {
  // Straight at 1 m/s for 2 s: Gamma(t, tau) columns are (1,0,0), (0,1,0), (-(y_t - y), x_t - x, 1)
  // = (0, 2 - tau, 1); their integrals: input[0](0,0) = 2, input[1](1,1) = 2,
  // input[2](1,1) = integral (2 - tau)^2 = 8/3, input[2](1,2) = integral (2 - tau) = 2.
  const std::array<double, ipd::kAlphaSize> alpha{};
  const Eigen::Matrix3d sigma = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
  const ipd::PredictionCovarianceTerms t =
      ipd::PredictionCovariance(Straight(1.0, 2.0, 0.001), alpha.data(), 9.81, sigma, sigma);
  EXPECT_NEAR(t.input[0](0, 0), 2.0, 1e-9);
  EXPECT_NEAR(t.input[1](1, 1), 2.0, 1e-9);
  EXPECT_NEAR(t.input[2](1, 1), 8.0 / 3.0, 5e-3);
  EXPECT_NEAR(t.input[2](1, 2), 2.0, 5e-3);
  EXPECT_NEAR(t.input[2](2, 2), 2.0, 1e-9);
  // Start-pose heading error swings the end by the 2 m lever: 1e-4 + 4 x 1e-6 (+ the end's 1e-4).
  EXPECT_NEAR(t.measurement(1, 1), 2e-4 + 4e-6, 1e-12);
  const Eigen::Matrix3d total = t.Total({0.1, 0.2, 0.3});
  EXPECT_NEAR(total(0, 0), t.measurement(0, 0) + 0.1 * 2.0, 1e-9);
}

TEST(IpdSegment, RelativePoseInTheStartFrame) {
  const Eigen::Vector3d z = ipd::RelativePose(1.0, 1.0, M_PI / 2, 1.0, 3.0, -3.0);
  EXPECT_NEAR(z[0], 2.0, 1e-12);  // 2 m ahead of a robot facing +y
  EXPECT_NEAR(z[1], 0.0, 1e-12);
  EXPECT_NEAR(z[2], std::remainder(-3.0 - M_PI / 2, 2 * M_PI), 1e-12);
}

}  // namespace
}  // namespace slipgraph

#include "factors/ipd_segment_factor.h"
#include "tests/factor_check.h"

namespace slipgraph {
namespace {

TEST(IpdSegmentFactor, ResidualAndJacobian) {
  std::vector<ipd::OdometryStep> steps;
  for (int k = 0; k < 200; ++k) {
    steps.push_back({0.01, 1.0, 0.3, 0.02, -0.05});
  }
  std::array<double, ipd::kAlphaSize> alpha{};
  double predicted[3];
  ipd::PredictSegment(steps, alpha.data(), 9.81, predicted);
  // Measured: the no-slip prediction plus (0.1, 0, 0): residual = L^-1 (0.1, 0, 0).
  const Eigen::Vector3d measured(predicted[0] + 0.1, predicted[1], predicted[2]);
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.01, 0.04, 0.0001).asDiagonal();
  const std::unique_ptr<ceres::CostFunction> f(
      IpdSegmentFactor::Create(steps, measured, covariance, 9.81));
  const std::vector<double> r = testing::Residuals(*f, {alpha.data()});
  EXPECT_NEAR(r[0], 1.0, 1e-9);
  EXPECT_NEAR(r[1], 0.0, 1e-9);
  EXPECT_NEAR(r[2], 0.0, 1e-9);
  for (int i = 0; i < ipd::kAlphaSize; ++i) alpha[i] = 0.02 * (i % 5) - 0.04;
  testing::ExpectJacobiansMatchNumeric(*f, {alpha.data()});
}

}  // namespace
}  // namespace slipgraph
