#include "solvers/ward_updaters.h"

#include <ceres/jet.h>

#include <algorithm>
#include <cmath>

#include "factors/frames.h"
#include "factors/tire_law_uncertainty.h"

namespace slipgraph {

using namespace ward;  // NOLINT: state and measurement indices

ekf::MeasurementRows ImuRows(const ekf::StateVector& x, const ImuSample& imu,
                             const AttitudeLoads<double>& loads, const ImuOffsets<double>& offsets,
                             const Params& params, const ModelConfig& model,
                             bool accelerometer_driven, double imu_period_s) {
  using Jet = ceres::Jet<double, kStateSize>;
  Jet x_jet[kStateSize], z[kMeasurementSize];
  for (int i = 0; i < kStateSize; ++i) x_jet[i] = Jet(x(i), i);
  TireForces<Jet> forces;
  PredictMeasurements(x_jet, loads, offsets, params, z, &forces);
  const SensorNoise& noise = model.measurement;
  ekf::MeasurementRows rows;
  if (std::isfinite(imu.ax)) {
    double variance = noise.imu_sd_accel_mps2 * noise.imu_sd_accel_mps2;
    if (accelerometer_driven) {
      // From the row's own forces (their Jets carry d/d w): no second tire-force evaluation.
      variance +=
          TireLawVarianceOf(forces, kOmegaLeft, kOmegaRight, params, model.tire_uncertainty) *
          TireLawSampleScale(model.tire_uncertainty, imu_period_s);
    }
    rows.Add(imu.ax - z[kZAccelX].a, z[kZAccelX].v.transpose(), variance, "accelerometer");
  }
  if (std::isfinite(imu.gz)) {
    rows.Add(imu.gz - z[kZYawRate].a, z[kZYawRate].v.transpose(),
             noise.imu_sd_gyro_radps * noise.imu_sd_gyro_radps, "gyro");
  }
  return rows;
}

ekf::MeasurementRows WheelRows(const ekf::StateVector& x, double omega_left_radps,
                               double omega_right_radps, double sd_omega_radps) {
  const double variance = sd_omega_radps * sd_omega_radps;
  ekf::MeasurementRows rows;
  if (std::isfinite(omega_left_radps)) {
    rows.AddOnState(kOmegaLeft, omega_left_radps - x(kOmegaLeft), variance, "encoder_left");
  }
  if (std::isfinite(omega_right_radps)) {
    rows.AddOnState(kOmegaRight, omega_right_radps - x(kOmegaRight), variance, "encoder_right");
  }
  return rows;
}

ekf::MeasurementRows GnssRows(const ekf::StateVector& x, const GpsSample& gps,
                              const GnssAttitude& attitude, double stated_sd_mps) {
  const double along =
      GnssVelocityAlongBodyX(gps.vx, gps.vy, gps.vz, attitude.known, attitude.pitch_rad,
                             attitude.yaw_rad, x(kOmegaLeft) + x(kOmegaRight));
  const double sd = GnssVelocitySd(gps, stated_sd_mps);
  ekf::MeasurementRows rows;
  rows.AddOnState(kVbx, along - x(kVbx), sd * sd, "gnss");
  return rows;
}

double GnssFading::ScaleFor(double innovation, double predicted_variance, bool gate_lets_in) {
  const double z = innovation / std::sqrt(predicted_variance);
  if (z * z > gate_chi2_) {
    if (gate_lets_in) ema_ += weight_ * (std::copysign(std::sqrt(gate_chi2_), z) - ema_);
    return 1.0;
  }
  ema_ += weight_ * (z - ema_);
  if (std::abs(ema_) > threshold_ && z * ema_ > 1.0 && std::abs(z) > 1.0) {
    return std::min(max_scale_, z * z);
  }
  return 1.0;
}

}  // namespace slipgraph
