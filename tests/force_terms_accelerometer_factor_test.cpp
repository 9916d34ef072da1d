// The accelerometer factor with registered force terms: with the terms' magnitudes at 0 it is
// EffectAccelerometerFactor exactly; its Jacobian (the catalogue part by automatic
// differentiation, each term's by its own Jets) matches numeric differentiation; and a term adds
// phi h(x, c) to the prediction, per unit of the accelerometer's sd.
#include "factors/force_terms_accelerometer_factor.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "tests/factor_check.h"

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
  // One magnitude per model effect, load transfer's included (the factor reads the whole block).
  std::array<double, kModelEffectCount> theta = {30.0, 0.1, 2.0, 0.02, 0.05, -0.2, 1.5};
  static_assert(kModelEffectCount == 7, "give the new effect a magnitude above");
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
  // The factor's residual and the catalogue-only factor's at the same blocks.
  std::pair<double, double> Residuals() const {
    const double* blocks[] = {x.data(), offsets.data(), theta.data(), phi.data()};
    double r = 0.0, r_effects = 0.0;
    EXPECT_TRUE(Factor()->Evaluate(blocks, &r, nullptr));
    const std::unique_ptr<ceres::CostFunction> effects(EffectAccelerometerFactor::Create(
        params, context.attitude, context.accel_x_mps2, 0.08, windows));
    EXPECT_TRUE(effects->Evaluate(blocks, &r_effects, nullptr));
    return {r, r_effects};
  }
};

TEST(ForceTermsAccelerometerFactor, IsTheEffectFactorWithTheTermsAtZero) {
  Fixture f;
  f.phi = {0.0, 0.0};
  const auto [r, r_effects] = f.Residuals();
  EXPECT_EQ(r, r_effects);
}

TEST(ForceTermsAccelerometerFactor, AddsEachTermToThePrediction) {
  Fixture f;
  const auto [r, r_effects] = f.Residuals();
  // By hand: h = -v yaw^2 / m + sin(pitch) + 0.1 w_l a_x.
  const double h = -0.7 * 0.09 / 117.0 + std::sin(-0.05) + 0.1 * 6.5 * 0.35;
  EXPECT_NEAR(r, r_effects - (0.4 - 1.3) * h / 0.08, 1e-12);
}

TEST(ForceTermsAccelerometerFactor, JacobianMatchesNumeric) {
  Fixture f;
  const std::unique_ptr<ceres::CostFunction> factor = f.Factor();
  testing::ExpectJacobiansMatchNumeric(
      *factor, {f.x.data(), f.offsets.data(), f.theta.data(), f.phi.data()}, 1e-6);
}

}  // namespace
}  // namespace slipgraph
