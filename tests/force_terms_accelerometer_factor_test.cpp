// The accelerometer factor with registered force terms: with the terms' magnitudes at 0 it is
// EffectAccelerometerFactor exactly; its Jacobian (the catalogue part by automatic
// differentiation, each term's by its own Jets) matches central differences; and a term adds
// phi h(x, c) to the prediction, per unit of the accelerometer's sd.
#include "factors/force_terms_accelerometer_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace slipgraph {
namespace {

// A shape that uses the state nonlinearly and the context.
struct TestShape {
  template <typename T>
  T operator()(const T* x, const ForceTermContext& c, const ward::Params& p) const {
    using std::sin;
    return -x[ward::kVbx] * x[ward::kYawRate] * x[ward::kYawRate] / p.mass_kg +
           sin(T(c.attitude.pitch_rad)) + 0.1 * x[ward::kOmegaLeft] * c.accel_x_mps2;
  }
};

struct Fixture {
  ward::Params params;
  ForceTermContext context;
  ForceTerm first = MakeForceTerm<TestShape>("test_shape", "-", 1.0, "");
  ForceTerm second = MakeForceTerm<TestShape>("test_shape_2", "-", 1.0, "");
  std::vector<double> x = {0.7, 0.01, -0.2, 6.5, 7.1, 0.3, 0.002};
  std::vector<double> offsets = {0.05, -0.001};
  std::vector<double> theta = {30.0, 0.1, 2.0, 0.02, 0.05, -0.2};
  std::vector<double> phi = {0.4, -1.3};
  EffectWindowWeights windows{1.0, 1.0};
  Fixture() {
    params.mass_kg = 117.0;
    context.t_s = 3.0;
    context.attitude = {0.02, -0.05};
    context.accel_x_mps2 = 0.35;
  }
  std::unique_ptr<ceres::CostFunction> Factor() const {
    return std::make_unique<ForceTermsAccelerometerFactor>(
        params, context, 0.08, windows, std::vector<const ForceTerm*>{&first, &second});
  }
};

TEST(ForceTermsAccelerometerFactor, IsTheEffectFactorWithTheTermsAtZero) {
  Fixture f;
  f.phi = {0.0, 0.0};
  const double* blocks[] = {f.x.data(), f.offsets.data(), f.theta.data(), f.phi.data()};
  double r = 0.0, r_effects = 0.0;
  ASSERT_TRUE(f.Factor()->Evaluate(blocks, &r, nullptr));
  std::unique_ptr<ceres::CostFunction> effects(EffectAccelerometerFactor::Create(
      f.params, f.context.attitude, f.context.accel_x_mps2, 0.08, f.windows));
  ASSERT_TRUE(effects->Evaluate(blocks, &r_effects, nullptr));
  EXPECT_EQ(r, r_effects);
}

TEST(ForceTermsAccelerometerFactor, AddsEachTermToThePrediction) {
  Fixture f;
  const double* blocks[] = {f.x.data(), f.offsets.data(), f.theta.data(), f.phi.data()};
  double r = 0.0, r_effects = 0.0;
  ASSERT_TRUE(f.Factor()->Evaluate(blocks, &r, nullptr));
  std::unique_ptr<ceres::CostFunction> effects(EffectAccelerometerFactor::Create(
      f.params, f.context.attitude, f.context.accel_x_mps2, 0.08, f.windows));
  ASSERT_TRUE(effects->Evaluate(blocks, &r_effects, nullptr));
  // By hand: h = -v yaw^2 / m + sin(pitch) + 0.1 w_l a_x.
  const double h = -0.7 * 0.09 / 117.0 + std::sin(-0.05) + 0.1 * 6.5 * 0.35;
  EXPECT_NEAR(r, r_effects - (0.4 - 1.3) * h / 0.08, 1e-12);
}

TEST(ForceTermsAccelerometerFactor, JacobianMatchesCentralDifferences) {
  Fixture f;
  std::vector<std::vector<double>*> values = {&f.x, &f.offsets, &f.theta, &f.phi};
  const std::unique_ptr<ceres::CostFunction> factor = f.Factor();
  const auto Residual = [&]() {
    const double* blocks[] = {f.x.data(), f.offsets.data(), f.theta.data(), f.phi.data()};
    double r = 0.0;
    EXPECT_TRUE(factor->Evaluate(blocks, &r, nullptr));
    return r;
  };
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> pointers;
  for (auto* v : values) jacobians.emplace_back(v->size(), 0.0);
  for (auto& j : jacobians) pointers.push_back(j.data());
  const double* blocks[] = {f.x.data(), f.offsets.data(), f.theta.data(), f.phi.data()};
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
