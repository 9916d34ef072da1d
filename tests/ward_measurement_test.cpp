#include "factors/ward_measurement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/jacobian_check.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT

const Params kParams = testing::LagrParams();

TEST(WardMeasurement, HandComputedPoint) {
  // Free rolling at 1 m/s: f_tire = -g (R1 (1 - e^-20) + R2); accelerometer adds offsets, bias
  // and disturbance; gyro adds offset and bias; GNSS reads v; encoders read the wheel speeds.
  const double x[kStateSize] = {1.0, 0.02, -0.5, 4.0, 4.0, 0.0, 0.003};
  const ImuOffsets<double> offsets{0.1, -0.01};
  double z[kMeasurementSize];
  PredictMeasurements(x, Attitude<double>{0.0, 0.0}, offsets, kParams, z);
  const double f_tire = -9.80665 * (0.03 * (1.0 - std::exp(-20.0)) + 0.01);
  EXPECT_NEAR(z[kZAccelX], f_tire + 0.1 + 0.02 - 0.5, 1e-12);
  EXPECT_NEAR(z[kZYawRate], 0.0 - 0.01 + 0.003, 1e-15);
  EXPECT_EQ(z[kZGpsVx], 1.0);
  EXPECT_EQ(z[kZOmegaLeft], 4.0);
  EXPECT_EQ(z[kZOmegaRight], 4.0);
}

TEST(WardMeasurement, AccelerometerOnASlopeAtRestReadsGravityComponent) {
  // Held still on a 0.1 rad uphill slope with brakes (a_dist balancing gravity): v' = 0 and the
  // accelerometer reads +g sin(phi) along body x.
  double x[kStateSize] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  x[kAdist] = 9.80665 * std::sin(0.1);
  double z[kMeasurementSize], x_dot[kStateSize];
  const Attitude<double> uphill{0.0, -0.1};
  PredictMeasurements(x, uphill, ImuOffsets<double>{0.0, 0.0}, kParams, z);
  StateDerivative(x, uphill, kParams, x_dot);
  EXPECT_NEAR(x_dot[kVbx], 0.0, 1e-12);
  EXPECT_NEAR(z[kZAccelX], 9.80665 * std::sin(0.1), 1e-12);
}

struct MeasurementFn {
  template <typename T>
  void operator()(const T* x, T* z) const {
    PredictMeasurements(x, Attitude<T>{T(0.02), T(0.03)}, ImuOffsets<T>{T(0.05), T(-0.002)},
                        kParams, z);
  }
};

TEST(WardMeasurement, JacobianMatchesCentralDifferences) {
  const double at_rest[kStateSize] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const double moving[kStateSize] = {0.7, 0.01, -1.0, 3.5, 2.5, -0.2, 0.001};
  for (const double* x : {at_rest, moving}) {
    const auto ad = testing::AutoDiffJacobian<kStateSize, kMeasurementSize>(MeasurementFn(), x);
    const auto nd =
        testing::CentralDifferenceJacobian<kStateSize, kMeasurementSize>(MeasurementFn(), x);
    EXPECT_LT(testing::MaxRelativeDifference(ad, nd), 1e-5);
  }
}

}  // namespace
}  // namespace slipgraph
