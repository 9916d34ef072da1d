// The accelerometer factor with the tire law's slip stiffness scaled: with theta = 0 it is the
// plain AccelerometerFactor; scaling v_rel by s is the law with At and C2 both scaled by s (a
// hand identity of eq. 8); theta is interpolated between its two nodes; the Jacobian matches
// numeric differentiation.
#include "factors/stiffness_accelerometer_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "factors/imu_factor.h"
#include "tests/factor_check.h"

namespace slipgraph {
namespace {

struct Fixture {
  ward::Params params;
  ward::Attitude<double> attitude{0.02, -0.05};
  std::vector<double> x = {0.7, 0.01, -0.2, 6.5, 7.1, 0.3, 0.002};
  std::vector<double> offsets = {0.05, -0.001};
  Fixture() {
    params.mass_kg = 117.0;
    params.tire = {0.475, 13.25, 0.068};
  }
};

TEST(StiffnessAccelerometerFactor, IsTheAccelerometerFactorAtTheLawsStiffness) {
  Fixture f;
  double zero_a = 0.0, zero_b = 0.0;
  const double* blocks[] = {f.x.data(), f.offsets.data(), &zero_a, &zero_b};
  std::unique_ptr<ceres::CostFunction> factor(
      StiffnessAccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, 0.4));
  std::unique_ptr<ceres::CostFunction> plain(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  double r = 0.0, r_plain = 0.0;
  ASSERT_TRUE(factor->Evaluate(blocks, &r, nullptr));
  ASSERT_TRUE(plain->Evaluate(blocks, &r_plain, nullptr));
  EXPECT_NEAR(r, r_plain, 1e-12);
}

TEST(StiffnessAccelerometerFactor, ScalesAtAndC2AndInterpolatesItsNodes) {
  Fixture f;
  // theta = (1 - u) theta_a + u theta_b = 0.6 * -0.4 + 0.4 * 0.1 = -0.2: s = 0.8.
  double theta_a = -0.4, theta_b = 0.1;
  const double* blocks[] = {f.x.data(), f.offsets.data(), &theta_a, &theta_b};
  std::unique_ptr<ceres::CostFunction> factor(
      StiffnessAccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, 0.4));
  double r = 0.0;
  ASSERT_TRUE(factor->Evaluate(blocks, &r, nullptr));
  ward::Params scaled = f.params;
  scaled.tire.At *= 0.8;
  scaled.tire.C2 *= 0.8;
  std::unique_ptr<ceres::CostFunction> plain(
      AccelerometerFactor::Create(scaled, f.attitude, 0.3, 0.08));
  double r_plain = 0.0;
  ASSERT_TRUE(plain->Evaluate(blocks, &r_plain, nullptr));
  EXPECT_NEAR(r, r_plain, 1e-12);
  // The scale matters at this slip: the law's own stiffness gives another residual.
  std::unique_ptr<ceres::CostFunction> law(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  double r_law = 0.0;
  ASSERT_TRUE(law->Evaluate(blocks, &r_law, nullptr));
  EXPECT_GT(std::abs(r - r_law), 1e-3);
}

TEST(StiffnessAccelerometerFactor, JacobianMatchesNumeric) {
  Fixture f;
  const std::vector<double> theta_a = {-0.3}, theta_b = {0.2};
  const std::unique_ptr<ceres::CostFunction> factor(
      StiffnessAccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, 0.25));
  testing::ExpectJacobiansMatchNumeric(
      *factor, {f.x.data(), f.offsets.data(), theta_a.data(), theta_b.data()}, 1e-6);
}

}  // namespace
}  // namespace slipgraph
