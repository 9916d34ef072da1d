#include "factors/ipd_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/jacobian_check.h"

namespace slipgraph {
namespace {

TEST(IpdKinematics, PoseRateHandComputed) {
  // Heading north (yaw = pi/2) on flat ground: forward speed moves +y, lateral (left) moves -x.
  const double u[3] = {1.0, 0.2, 0.3};
  double rho_dot[3];
  ipd::PoseRate(0.0, 0.0, M_PI / 2, u, rho_dot);
  EXPECT_NEAR(rho_dot[0], -0.2, 1e-15);
  EXPECT_NEAR(rho_dot[1], 1.0, 1e-15);
  EXPECT_NEAR(rho_dot[2], 0.3, 1e-15);
  // Pitched 0.2 rad: forward speed projects by cos(0.2); the yaw rate scales by c(g)/c(b).
  ipd::PoseRate(0.1, 0.2, 0.0, u, rho_dot);
  EXPECT_NEAR(rho_dot[0], std::cos(0.2) * 1.0 + std::sin(0.2) * std::sin(0.1) * 0.2, 1e-15);
  EXPECT_NEAR(rho_dot[1], std::cos(0.1) * 0.2, 1e-15);
  EXPECT_NEAR(rho_dot[2], std::cos(0.1) / std::cos(0.2) * 0.3, 1e-15);
}

TEST(IpdKinematics, SlipVelocitiesHandComputed) {
  double alpha[ipd::kAlphaSize];
  for (int i = 0; i < ipd::kAlphaSize; ++i) alpha[i] = 0.01 * (i + 1);
  double u_s[3];
  const double v = 1.5, w = -0.4, gx = 0.3, gy = -0.2;
  ipd::SlipVelocities(v, w, gx, gy, alpha, u_s);
  const double abs_w = std::sqrt(w * w + 1e-8) - 1e-4;  // smooth |w|, within eps = 1e-4
  EXPECT_NEAR(abs_w, 0.4, 1e-4);
  EXPECT_NEAR(u_s[0], 0.01 * v + 0.02 * abs_w + 0.03 * v * abs_w + 0.04 * gx, 1e-15);
  EXPECT_NEAR(u_s[1], 0.05 * v + 0.06 * w + 0.07 * v * w + 0.08 * gy, 1e-15);
  EXPECT_NEAR(u_s[2], 0.09 * v + 0.10 * w + 0.11 * v * w + 0.12 * gx + 0.13 * gy, 1e-15);
}

TEST(IpdKinematics, GravityInBodyPointsDownhill) {
  double gx, gy;
  ipd::GravityInBody(0.0, 0.1, 9.8, &gx, &gy);  // nose down 0.1 rad: gravity pulls forward
  EXPECT_NEAR(gx, 9.8 * std::sin(0.1), 1e-12);
  EXPECT_NEAR(gy, 0.0, 1e-12);
  ipd::GravityInBody(0.1, 0.0, 9.8, &gx, &gy);  // right side down: gravity pulls right (-y)
  EXPECT_NEAR(gy, -9.8 * std::sin(0.1), 1e-12);
}

// Slip velocities as a function of (v, w, g_x, g_y, alpha[13]).
struct SlipFn {
  template <typename T>
  void operator()(const T* x, T* y) const {
    ipd::SlipVelocities(x[0], x[1], x[2], x[3], x + 4, y);
  }
};

struct PoseRateFn {
  template <typename T>
  void operator()(const T* x, T* y) const {
    ipd::PoseRate(x[0], x[1], x[2], x + 3, y);
  }
};

TEST(IpdKinematics, JacobiansMatchCentralDifferencesIncludingZeroYawRate) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    double x[17];
    for (double& value : x) value = u(rng);
    if (trial == 0) x[1] = 0.0;  // |V_yaw| at its kink
    const auto ad = testing::AutoDiffJacobian<17, 3>(SlipFn(), x);
    const auto nd = testing::CentralDifferenceJacobian<17, 3>(SlipFn(), x, 1e-7);
    EXPECT_LT(testing::MaxRelativeDifference(ad, nd), 1e-5) << "trial " << trial;
    double p[6] = {0.3 * u(rng), 0.3 * u(rng), 3.0 * u(rng), u(rng), u(rng), u(rng)};
    const auto ad_p = testing::AutoDiffJacobian<6, 3>(PoseRateFn(), p);
    const auto nd_p = testing::CentralDifferenceJacobian<6, 3>(PoseRateFn(), p);
    EXPECT_LT(testing::MaxRelativeDifference(ad_p, nd_p), 1e-6);
  }
}

}  // namespace
}  // namespace slipgraph
