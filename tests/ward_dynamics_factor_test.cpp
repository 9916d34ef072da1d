#include "factors/ward_dynamics_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "tests/factor_check.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT

const Params kParams = testing::LagrParams();
const std::array<double, 6> kSd = {0.01, 0.001, 0.1, 0.1, 0.05, 0.0001};

TEST(WardDynamicsFactor, ZeroResidualAtThePropagatedState) {
  const double x[kStateSize] = {0.8, 0.01, -0.3, 3.3, 3.4, 0.1, 0.001};
  const double offsets[2] = {0.05, -0.002};
  double next[kStateSize];
  Propagate(x, Attitude<double>{0.02, -0.05}, kParams, 0.01, next);
  const std::unique_ptr<ceres::CostFunction> f(
      WardDynamicsFactor::Create(kParams, {0.02, -0.05}, 0.01, std::nan(""), kSd));
  for (double r : testing::Residuals(*f, {x, next, offsets})) EXPECT_NEAR(r, 0.0, 1e-12);
}

TEST(WardDynamicsFactor, AccelerometerDrivenVelocityHandComputed) {
  // Flat ground, a_x = 0.5, c_ax = 0.1, b_ax = 0.02 decaying with tau: over 0.01 s from 1.0,
  // v = 1 + (0.5 - 0.1) 0.01 - 0.02 tau (1 - exp(-0.01 / tau)) = 1.0038 - 3.3e-9.
  const double x[kStateSize] = {1.0, 0.02, 0.0, 4.0, 4.0, 0.0, 0.0};
  const double offsets[2] = {0.1, 0.0};
  double next[kStateSize];
  std::copy(x, x + kStateSize, next);
  next[kVbx] = 1.0048;
  next[kAccelBias] = 0.02 * std::exp(-0.01 / kParams.accel_bias_tau_s);
  const std::unique_ptr<ceres::CostFunction> f(
      WardDynamicsFactor::Create(kParams, {0.0, 0.0}, 0.01, 0.5, kSd));
  const std::vector<double> r = testing::Residuals(*f, {x, next, offsets});
  const double tau = kParams.accel_bias_tau_s;
  const double predicted = 1.0 + 0.4 * 0.01 - 0.02 * tau * (1.0 - std::exp(-0.01 / tau));
  EXPECT_NEAR(r[0], (1.0048 - predicted) / 0.01, 1e-9);
  EXPECT_NEAR(r[1], 0.0, 1e-9);
}

TEST(WardDynamicsFactor, JacobiansMatchNumericAtRandomAndZeroVelocityPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double offsets[2] = {0.05, -0.002};
  for (int trial = 0; trial < 6; ++trial) {
    double x[kStateSize] = {u(rng),     0.01 * u(rng), u(rng),        4 * u(rng),
                            4 * u(rng), 0.3 * u(rng),  0.001 * u(rng)};
    if (trial == 0) std::fill(x, x + kStateSize, 0.0);  // at rest: v_rel = v_fwd = 0
    double next[kStateSize];
    for (int i = 0; i < kStateSize; ++i) next[i] = x[i] + 0.01 * u(rng);
    for (double accel : {std::nan(""), 0.3}) {
      const std::unique_ptr<ceres::CostFunction> f(
          WardDynamicsFactor::Create(kParams, {0.03, -0.04}, 0.01, accel, kSd));
      testing::ExpectJacobiansMatchNumeric(*f, {x, next, offsets}, 1e-5);
    }
  }
}

// The problems' factor differentiates x_k and c_ax only (x_{k+1} enters linearly): the same
// residuals and Jacobians as automatic differentiation of all three blocks.
TEST(WardDynamicsFactor, AsAutomaticDifferentiationOfEveryBlock) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double offsets[2] = {0.05, -0.002};
  for (int trial = 0; trial < 6; ++trial) {
    const double x[kStateSize] = {u(rng),     0.01 * u(rng), u(rng),        4 * u(rng),
                                  4 * u(rng), 0.3 * u(rng),  0.001 * u(rng)};
    double next[kStateSize];
    for (int i = 0; i < kStateSize; ++i) next[i] = x[i] + 0.01 * u(rng);
    for (double accel : {std::nan(""), 0.3}) {
      const std::unique_ptr<ceres::CostFunction> f(
          WardDynamicsFactor::Create(kParams, {0.03, -0.04}, 0.01, accel, kSd));
      const std::unique_ptr<ceres::CostFunction> reference(
          WardDynamicsFactor::CreateAutoDiff(kParams, {0.03, -0.04}, 0.01, accel, kSd));
      const double* blocks[] = {x, next, offsets};
      double r[6], r_ref[6], j0[42], j1[42], j2[12], k0[42], k1[42], k2[12];
      double* jac[] = {j0, j1, j2};
      double* ref[] = {k0, k1, k2};
      ASSERT_TRUE(f->Evaluate(blocks, r, jac));
      ASSERT_TRUE(reference->Evaluate(blocks, r_ref, ref));
      for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(r[i], r_ref[i], 1e-9 * std::max(1.0, std::abs(r_ref[i])));
      for (int i = 0; i < 42; ++i) EXPECT_NEAR(j0[i], k0[i], 1e-9 * std::max(1.0, std::abs(k0[i])));
      for (int i = 0; i < 42; ++i) EXPECT_EQ(j1[i], k1[i]);
      for (int i = 0; i < 12; ++i) EXPECT_NEAR(j2[i], k2[i], 1e-9 * std::max(1.0, std::abs(k2[i])));
      // Without Jacobians: the same residuals on doubles.
      double r_plain[6];
      ASSERT_TRUE(f->Evaluate(blocks, r_plain, nullptr));
      for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(r_plain[i], r_ref[i], 1e-12 * std::max(1.0, std::abs(r_ref[i])));
    }
  }
}

}  // namespace
}  // namespace slipgraph
