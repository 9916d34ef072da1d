// The accelerometer factor with the law and the radii as unknowns: at the model's law and zero
// radius errors it is the plain AccelerometerFactor; at another law it is AccelerometerFactor
// built with that law (At too, through the saturation's argument); a radius error is the wheel
// speed scaled on its side; the Jacobian matches numeric differentiation.
#include "factors/law_accelerometer_factor.h"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "factors/imu_factor.h"
#include "tests/factor_check.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

// The LAGR robot with the law the user of ward21 states (the soils' mean), at a turning state.
struct Fixture {
  ward::Params params = testing::LagrParams();
  ward::Attitude<double> attitude{0.02, -0.05};
  std::vector<double> x = {0.7, 0.01, -0.2, 6.5, 7.1, 0.3, 0.002};
  std::vector<double> offsets = {0.05, -0.001};
  Fixture() {
    params.tire = {0.475, 13.25, 0.068};
    params.rolling = {0.0625, 16.25, 0.02};
  }
};

double Residual(const ceres::CostFunction& cost, const std::vector<const double*>& blocks) {
  return testing::Residuals(cost, blocks).at(0);
}

TEST(LawAccelerometerFactor, IsTheAccelerometerFactorOfTheLawItIsGiven) {
  Fixture f;
  std::unique_ptr<ceres::CostFunction> factor(
      LawAccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  const std::array<double, 2> no_error = {0.0, 0.0};
  std::array<double, kLawCoefficientCount> law = LawCoefficients(f.params.tire, f.params.rolling);
  std::unique_ptr<ceres::CostFunction> plain(
      AccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  EXPECT_NEAR(Residual(*factor, {f.x.data(), f.offsets.data(), law.data(), no_error.data()}),
              Residual(*plain, {f.x.data(), f.offsets.data()}), 1e-12);

  // Another law (every coefficient moved): the factor built with the model's law, given the
  // other law as its block, is the plain factor of a model with the other law.
  law = {0.6, 21.0, 0.03, 0.04, 0.05};
  ward::Params other = f.params;
  SetLawCoefficients(law, &other.tire, &other.rolling);
  std::unique_ptr<ceres::CostFunction> plain_other(
      AccelerometerFactor::Create(other, f.attitude, 0.3, 0.08));
  const double r = Residual(*factor, {f.x.data(), f.offsets.data(), law.data(), no_error.data()});
  EXPECT_NEAR(r, Residual(*plain_other, {f.x.data(), f.offsets.data()}), 1e-12);
  // Control: it is not the model's law's residual.
  EXPECT_GT(std::abs(r - Residual(*plain, {f.x.data(), f.offsets.data()})), 0.1);
}

TEST(LawAccelerometerFactor, ARadiusErrorScalesItsSidesWheelSpeed) {
  Fixture f;
  std::unique_ptr<ceres::CostFunction> factor(
      LawAccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  const std::array<double, kLawCoefficientCount> law =
      LawCoefficients(f.params.tire, f.params.rolling);
  const std::array<double, 2> errors = {0.03, -0.02};
  std::vector<double> scaled = f.x;
  scaled[ward::kOmegaLeft] *= 1.03;
  scaled[ward::kOmegaRight] *= 0.98;
  const std::array<double, 2> none = {0.0, 0.0};
  EXPECT_NEAR(Residual(*factor, {f.x.data(), f.offsets.data(), law.data(), errors.data()}),
              Residual(*factor, {scaled.data(), f.offsets.data(), law.data(), none.data()}), 1e-12);
}

TEST(LawAccelerometerFactor, JacobiansMatchNumeric) {
  Fixture f;
  std::unique_ptr<ceres::CostFunction> factor(
      LawAccelerometerFactor::Create(f.params, f.attitude, 0.3, 0.08));
  const std::array<double, kLawCoefficientCount> law = {0.6, 21.0, 0.03, 0.04, 0.05};
  const std::array<double, 2> errors = {0.03, -0.02};
  // A driving slip (v_rel about 0.05 and 0.1 m/s, where At matters) and one near zero relative
  // velocity, where the saturation bends most.
  for (double v_rel : {0.05, 0.002}) {
    std::vector<double> x = f.x;
    x[ward::kOmegaLeft] = (x[ward::kVbx] + v_rel) / 0.25 / 1.03;
    x[ward::kOmegaRight] = (x[ward::kVbx] + 2.0 * v_rel) / 0.25 / 0.98;
    x[ward::kYawRate] = 0.0;
    testing::ExpectJacobiansMatchNumeric(*factor,
                                         {x.data(), f.offsets.data(), law.data(), errors.data()});
  }
}

}  // namespace
}  // namespace slipgraph
