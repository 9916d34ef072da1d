// The measurement factors of eq. (11): accelerometer, yaw gyro, encoders, GNSS velocity.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "factors/accelerometer_factor.h"
#include "factors/encoder_factor.h"
#include "factors/gnss_velocity_factor.h"
#include "factors/imu_factor.h"
#include "tests/factor_check.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT

const Params kParams = testing::LagrParams();

TEST(AccelerometerFactor, HandComputedResidualAndJacobians) {
  // Free rolling at 1 m/s (v_rel = 0): f_tire = -g (R1 (1 - e^-20) + R2).
  const double x[kStateSize] = {1.0, 0.02, -0.5, 4.0, 4.0, 0.0, 0.003};
  const double offsets[2] = {0.1, -0.01};
  const double f_tire = -9.80665 * (0.03 * (1.0 - std::exp(-20.0)) + 0.01);
  const double measured = 0.2;
  const std::unique_ptr<ceres::CostFunction> f(
      AccelerometerFactor::Create(kParams, {0.0, 0.0}, measured, 0.25));
  const std::vector<double> r = testing::Residuals(*f, {x, offsets});
  EXPECT_NEAR(r[0], (measured - (f_tire + 0.1 + 0.02 - 0.5)) / 0.25, 1e-12);
  // v_rel = 0 (and v = w = 0 at rest) are where the smoothed laws' second derivatives jump: a
  // finite-difference step h then errs by about A_t h relative (4e-6 here), hence 1e-5.
  testing::ExpectJacobiansMatchNumeric(*f, {x, offsets}, 1e-5);
  const double at_rest[kStateSize] = {0, 0, 0, 0, 0, 0, 0};
  testing::ExpectJacobiansMatchNumeric(*f, {at_rest, offsets}, 1e-5);
  const double slipping[kStateSize] = {0.6, 0.02, -1.5, 3.0, 3.4, 0.2, 0.003};
  testing::ExpectJacobiansMatchNumeric(*f, {slipping, offsets});
}

TEST(YawGyroFactor, HandComputedResidualAndJacobians) {
  const double x[kStateSize] = {1.0, 0.0, 0.0, 4.0, 4.0, 0.3, 0.002};
  const double offsets[2] = {0.0, 0.01};
  const std::unique_ptr<ceres::CostFunction> f(YawGyroFactor::Create(0.32, 0.005));
  EXPECT_NEAR(testing::Residuals(*f, {x, offsets})[0], (0.32 - 0.312) / 0.005, 1e-9);
  testing::ExpectJacobiansMatchNumeric(*f, {x, offsets});
}

TEST(EncoderFactor, HandComputedResidualAndJacobians) {
  const double x[kStateSize] = {1.0, 0.0, 0.0, 4.0, 4.2, 0.0, 0.0};
  const std::unique_ptr<ceres::CostFunction> f(EncoderFactor::Create(4.1, 4.2, 0.05));
  const std::vector<double> r = testing::Residuals(*f, {x});
  EXPECT_NEAR(r[0], 2.0, 1e-9);
  EXPECT_NEAR(r[1], 0.0, 1e-12);
  testing::ExpectJacobiansMatchNumeric(*f, {x});
}

TEST(GnssVelocityFactor, HandComputedResidualAndJacobians) {
  const double x[kStateSize] = {0.9, 0.0, 0.0, 4.0, 4.0, 0.0, 0.0};
  const std::unique_ptr<ceres::CostFunction> f(GnssVelocityFactor::Create(1.0, 0.1));
  EXPECT_NEAR(testing::Residuals(*f, {x})[0], 1.0, 1e-9);
  testing::ExpectJacobiansMatchNumeric(*f, {x});
}

}  // namespace
}  // namespace slipgraph
