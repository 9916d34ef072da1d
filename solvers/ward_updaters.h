// The rows each sensor gives the EKF at its current state (eq. 11, factors/ward_measurement.h),
// and the GNSS fading memory: what WardEkf's updates apply through ekf::ApplySequentialUpdate.
// Each row is named for the recorded innovations ("accelerometer", "gyro", "encoder_left",
// "encoder_right", "gnss").
#pragma once

#include "factors/ward_dynamics.h"
#include "factors/ward_measurement.h"
#include "io/drive_log.h"
#include "model/model_config.h"
#include "solvers/ekf_update.h"

namespace slipgraph {

// The accelerometer x (when finite) and the yaw gyro (when finite) against eq. (11)'s
// prediction at x. Accelerometer-driven, the accelerometer row ties a_dist to the tire law, so
// its noise is the tire law's too (persistent over the law's correlation time, per sample
// scaled by correlation_time / imu_period_s).
ekf::MeasurementRows ImuRows(const ekf::StateVector& x, const ImuSample& imu,
                             const ward::AttitudeLoads<double>& loads,
                             const ward::ImuOffsets<double>& offsets, const ward::Params& params,
                             const ModelConfig& model, bool accelerometer_driven,
                             double imu_period_s);

// The driven sides' encoder speeds (each when finite) on the wheel-speed states.
ekf::MeasurementRows WheelRows(const ekf::StateVector& x, double omega_left_radps,
                               double omega_right_radps, double sd_omega_radps);

// A GNSS velocity along body x (factors/frames.h GnssVelocityAlongBodyX) on v_bx, with the fix's
// own sd or the model's.
struct GnssAttitude {
  bool known = false;
  double pitch_rad = 0.0, yaw_rad = 0.0;
};
ekf::MeasurementRows GnssRows(const ekf::StateVector& x, const GpsSample& gps,
                              const GnssAttitude& attitude, double stated_sd_mps);

// Fading memory on GNSS (EkfOptions::gnss_fading_*): an EMA over about `fixes` fixes of the
// innovations normalized by their predicted sd, z = nu / sqrt(P_vv + r). When the average passes
// `threshold` and a fix with |z| > 1 agrees with it (z times the average above 1) and would pass
// the gate, the covariance is to be scaled by z^2 (at most `max_scale`) before the update, so
// that the fix can pull a drifting velocity back. Never shrinks P; never for a fix beyond the gate
// (an outlier must not open the covariance for itself). A fix the gate leaves out stays out of
// the average too: one glitch of the receiver (a position jump read as a velocity) would
// otherwise hold the average past the threshold for several fixes, and the next fixes, the
// glitch's neighbours, would open the covariance. A fix beyond the gate that the gate lets in
// (after a rejection) enters at the gate's z.
class GnssFading {
 public:
  GnssFading(double fixes, double threshold, double max_scale, double gate_chi2)
      : weight_(1.0 / fixes), threshold_(threshold), max_scale_(max_scale), gate_chi2_(gate_chi2) {}
  // The factor to scale P by before this fix's update (1: none). gate_lets_in: the gate would
  // apply this fix were it beyond the gate (it has rejected enough in a row).
  double ScaleFor(double innovation, double predicted_variance, bool gate_lets_in);

 private:
  double weight_, threshold_, max_scale_, gate_chi2_;
  double ema_ = 0.0;
};

}  // namespace slipgraph
