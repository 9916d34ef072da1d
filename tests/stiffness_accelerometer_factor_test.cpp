// The accelerometer factor with the tire law's slip stiffness scaled: with theta = 0 it is the
// plain AccelerometerFactor; scaling v_rel by s is the law with At and C2 both scaled by s (a
// hand identity of eq. 8); theta is interpolated between its two nodes; the Jacobian matches
// central differences.
#include "factors/stiffness_accelerometer_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "factors/imu_factor.h"

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

TEST(StiffnessAccelerometerFactor, JacobianMatchesCentralDifferences) {
  Fixture f;
  std::vector<double> theta_a = {-0.3}, theta_b = {0.2};
  std::vector<std::vector<double>*> values = {&f.x, &f.offsets, &theta_a, &theta_b};
  std::unique_ptr<ceres::CostFunction> factor(
      StiffnessAccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08, 0.25));
  const auto Residual = [&]() {
    const double* blocks[] = {f.x.data(), f.offsets.data(), theta_a.data(), theta_b.data()};
    double r = 0.0;
    EXPECT_TRUE(factor->Evaluate(blocks, &r, nullptr));
    return r;
  };
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> pointers;
  for (auto* v : values) jacobians.emplace_back(v->size(), 0.0);
  for (auto& j : jacobians) pointers.push_back(j.data());
  const double* blocks[] = {f.x.data(), f.offsets.data(), theta_a.data(), theta_b.data()};
  double r = 0.0;
  ASSERT_TRUE(factor->Evaluate(blocks, &r, pointers.data()));
  for (size_t b = 0; b < values.size(); ++b) {
    for (size_t i = 0; i < values[b]->size(); ++i) {
      double& p = (*values[b])[i];
      const double step = 1e-6 * std::max(1.0, std::abs(p)), saved = p;
      p = saved + step;
      const double plus = Residual();
      p = saved - step;
      const double minus = Residual();
      p = saved;
      const double numeric = (plus - minus) / (2.0 * step);
      EXPECT_NEAR(jacobians[b][i], numeric, 1e-5 * std::max(1.0, std::abs(numeric)))
          << "block " << b << " entry " << i;
    }
  }
}

}  // namespace
}  // namespace slipgraph
