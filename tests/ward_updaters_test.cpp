// The EKF's measurement rows: the IMU rows' Jacobians against central differences of eq. (11),
// NaN components left out, the encoder and GNSS rows on their states, and the GNSS fading
// memory opening the covariance only for a run of same-sign innovations that pass the gate.
#include "solvers/ward_updaters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices

const Params kParams = testing::LagrParams();

ekf::StateVector Moving() { return testing::MovingWardState(); }

TEST(WardUpdaters, ImuRowsAreEquationElevenWithItsJacobian) {
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(Attitude<double>{0.02, -0.05}, kParams);
  const ImuOffsets<double> offsets{0.1, -0.002};
  ModelConfig model;
  ImuSample imu;
  imu.ax = 0.4;
  imu.gz = 0.05;
  const ekf::MeasurementRows rows =
      ImuRows(Moving(), imu, loads, offsets, kParams, model, true, 0.01);
  ASSERT_EQ(rows.size(), 2);
  const auto predicted = [&](const ekf::StateVector& x, int index) {
    double z[kMeasurementSize];
    PredictMeasurements(x.data(), loads, offsets, kParams, z);
    return z[index];
  };
  EXPECT_NEAR(rows.innovation(0), imu.ax - predicted(Moving(), kZAccelX), 1e-12);
  EXPECT_NEAR(rows.innovation(1), imu.gz - predicted(Moving(), kZYawRate), 1e-12);
  for (int c = 0; c < kStateSize; ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(Moving()(c)));
    ekf::StateVector plus = Moving(), minus = Moving();
    plus(c) += h;
    minus(c) -= h;
    for (const int row : {0, 1}) {
      const int index = row == 0 ? kZAccelX : kZYawRate;
      const double numeric = (predicted(plus, index) - predicted(minus, index)) / (2.0 * h);
      EXPECT_NEAR(rows.jacobian(row)(c), numeric, 1e-5 * std::max(1.0, std::abs(numeric)))
          << "row " << row << " state " << c;
    }
  }
  EXPECT_DOUBLE_EQ(rows.variance(1),
                   model.measurement.imu_sd_gyro_radps * model.measurement.imu_sd_gyro_radps);
  EXPECT_GE(rows.variance(0),
            model.measurement.imu_sd_accel_mps2 * model.measurement.imu_sd_accel_mps2);
  EXPECT_STREQ(rows.name(0), "accelerometer");
  // A NaN accelerometer leaves the gyro alone.
  imu.ax = std::numeric_limits<double>::quiet_NaN();
  const ekf::MeasurementRows gyro_only =
      ImuRows(Moving(), imu, loads, offsets, kParams, model, true, 0.01);
  ASSERT_EQ(gyro_only.size(), 1);
  EXPECT_STREQ(gyro_only.name(0), "gyro");
}

TEST(WardUpdaters, EncoderAndGnssRowsSitOnTheirStates) {
  const ekf::MeasurementRows wheels =
      WheelRows(Moving(), 3.0, std::numeric_limits<double>::quiet_NaN(), 0.05);
  ASSERT_EQ(wheels.size(), 1);
  EXPECT_EQ(wheels.on_state(0), kOmegaLeft);
  EXPECT_DOUBLE_EQ(wheels.innovation(0), 3.0 - 3.4);
  EXPECT_DOUBLE_EQ(wheels.variance(0), 0.0025);

  GpsSample fix;
  fix.vx = 0.0;
  fix.vy = 1.0;  // north, the robot heading north (yaw 90 deg)
  const ekf::MeasurementRows gnss = GnssRows(Moving(), fix, {true, 0.0, M_PI / 2}, 0.1);
  ASSERT_EQ(gnss.size(), 1);
  EXPECT_EQ(gnss.on_state(0), kVbx);
  EXPECT_NEAR(gnss.innovation(0), 1.0 - 0.8, 1e-15);
  EXPECT_DOUBLE_EQ(gnss.variance(0), 0.01);
  fix.sd_v = 0.3;  // the fix's own sd wins
  EXPECT_DOUBLE_EQ(GnssRows(Moving(), fix, {}, 0.1).variance(0), 0.09);
}

TEST(WardUpdaters, FadingOpensOnlyForARunOfOneSign) {
  GnssFading fading(4.0, 0.5, 100.0, 15.1);
  // Alternating signs: never.
  for (int i = 0; i < 20; ++i) EXPECT_EQ(fading.ScaleFor(i % 2 ? 2.0 : -2.0, 1.0, false), 1.0);
  // A run of +2 sd: the average passes 0.5 and the scale is z^2 = 4.
  GnssFading run(4.0, 0.5, 100.0, 15.1);
  EXPECT_EQ(run.ScaleFor(2.0, 1.0, false), 1.0);  // average 0.5: not past the threshold
  EXPECT_DOUBLE_EQ(run.ScaleFor(2.0, 1.0, false), 4.0);
  // A fix the gate would reject does not open it, nor one of the other sign.
  EXPECT_EQ(run.ScaleFor(5.0, 1.0, false), 1.0);
  EXPECT_EQ(run.ScaleFor(-2.0, 1.0, false), 1.0);
  // At most max_scale.
  GnssFading capped(1.0, 0.5, 3.0, 15.1);
  EXPECT_DOUBLE_EQ(capped.ScaleFor(2.0, 1.0, false), 3.0);
}

TEST(WardUpdaters, FadingLeavesARejectedFixOutOfTheAverage) {
  // A glitch of -8 sd the gate rejects: the fixes after it, each at -1.5 sd, find the average
  // as the glitch's neighbours left it, 0.25 * -1.5 = -0.375 after the first, below 0.5.
  GnssFading glitch(4.0, 0.5, 100.0, 15.1);
  EXPECT_EQ(glitch.ScaleFor(-8.0, 1.0, false), 1.0);
  EXPECT_EQ(glitch.ScaleFor(-1.5, 1.0, false), 1.0);
  // Had the glitch counted, the average would be -2 + 0.25 * (-1.5 + 2) = -1.875 and the scale
  // 1.5^2; as it is, the same fix a second time finds -0.656, which z times is below 1.
  EXPECT_EQ(glitch.ScaleFor(-1.5, 1.0, false), 1.0);

  // Let in by the gate (after rejections in a row), a fix beyond it counts at the gate's z,
  // sqrt(15.1) = 3.886: the average becomes 0.25 * -3.886 = -0.971, past the threshold, and the
  // next fix of the same sign opens P by its z^2. The let-in fix itself never scales P.
  GnssFading let_in(4.0, 0.5, 100.0, 15.1);
  EXPECT_EQ(let_in.ScaleFor(-8.0, 1.0, true), 1.0);
  EXPECT_DOUBLE_EQ(let_in.ScaleFor(-1.5, 1.0, false), 2.25);
}

}  // namespace
}  // namespace slipgraph
