#include "sim/sensor_models.h"

#include <cmath>
#include <stdexcept>

#include "sim/random.h"

namespace slipgraph {
namespace sim {
namespace {

constexpr double kGravity = 9.80665;

}  // namespace

SensorSimulator::SensorSimulator(const SensorSpec& spec, const EffectSet& effects, int wheel_count,
                                 double step_s, std::mt19937_64* rng, DriveLog* log)
    : spec_(spec),
      effects_(effects),
      wheel_count_(wheel_count),
      step_s_(step_s),
      rng_(rng),
      log_(log) {
  imu_period_ = Period(spec.imu_rate_hz);
  wheel_period_ = Period(spec.wheel_rate_hz);
  gps_period_ = Period(spec.gps_rate_hz);
  attitude_period_ = Period(spec.attitude_rate_hz);
  pose_period_ = Period(spec.pose_rate_hz);
  command_period_ = Period(spec.command_rate_hz);
  UniformReal unit(-1.0, 1.0);
  for (int i = 0; i < 3; ++i) {
    imu_errors_.accel_offset_mps2[i] = spec.accel_offset_max_mps2 * unit(*rng_);
    imu_errors_.gyro_offset_radps[i] = spec.gyro_offset_max_radps * unit(*rng_);
    accel_bias_[i] = spec.accel_bias_sd_mps2 * normal_(*rng_);
    gyro_bias_[i] = spec.gyro_bias_sd_radps * normal_(*rng_);
  }
  const SensorMismatch& mismatch = spec.mismatch;
  if (mismatch.vibration_sd_mps2_per_mps > 0.0) {
    // z_k = a1 z_{k-1} + a2 z_{k-2} + g e_k, a damped resonance at vibration_hz sampled every
    // step; g sets its stationary variance to 1.
    const double theta = 2.0 * M_PI * mismatch.vibration_hz * step_s;
    const double radius = std::exp(-mismatch.vibration_damping * theta);
    vibration_a1_ = 2.0 * radius * std::cos(theta);
    vibration_a2_ = -radius * radius;
    vibration_gain_ =
        std::sqrt((1.0 + vibration_a2_) *
                  ((1.0 - vibration_a2_) * (1.0 - vibration_a2_) - vibration_a1_ * vibration_a1_) /
                  (1.0 - vibration_a2_));
  }
  if (mismatch.attitude_error_sd_rad > 0.0) {
    for (double& e : attitude_error_) e = mismatch.attitude_error_sd_rad * normal_(*rng_);
  }
  if (attitude_period_ > 0) log_->present_files.push_back("attitude.csv");
  if (gps_period_ > 0) log_->present_files.push_back("gps.csv");
  if (pose_period_ > 0) log_->present_files.push_back("pose.csv");
  if (command_period_ > 0) log_->present_files.push_back("commands.csv");
}

int64_t SensorSimulator::Period(double rate_hz) const {
  if (rate_hz <= 0.0) return 0;
  const double steps = 1.0 / (rate_hz * step_s_);
  const int64_t period = std::llround(steps);
  if (period < 1 || std::abs(steps - period) > 1e-6) {
    throw std::invalid_argument("sensor rate " + std::to_string(rate_hz) +
                                " Hz is not a whole number of simulation steps");
  }
  return period;
}

double SensorSimulator::Normal(double sd) { return sd * normal_(*rng_); }

void SensorSimulator::StepMismatch(const KinematicState& s) {
  const SensorMismatch& mismatch = spec_.mismatch;
  if (mismatch.vibration_sd_mps2_per_mps > 0.0) {
    for (int axis = 0; axis < 2; ++axis) {
      double* z = vibration_[axis];
      const double next =
          vibration_a1_ * z[0] + vibration_a2_ * z[1] + vibration_gain_ * normal_(*rng_);
      z[1] = z[0], z[0] = next;
      vibration_now_[axis] = mismatch.vibration_sd_mps2_per_mps * std::abs(s.v_bx) * next;
    }
  }
  if (mismatch.attitude_error_sd_rad > 0.0) {
    for (double& e : attitude_error_) {
      e = GaussMarkovStep(e, mismatch.attitude_error_sd_rad, mismatch.attitude_error_tau_s, step_s_,
                          normal_(*rng_));
    }
  }
}

void SensorSimulator::Observe(const KinematicState& s, int64_t step) {
  StepMismatch(s);
  if (imu_period_ > 0 && step % imu_period_ == 0) EmitImu(s);
  if (wheel_period_ > 0 && step % wheel_period_ == 0) EmitWheels(s);
  if (gps_period_ > 0 && step % gps_period_ == 0) EmitGps(s);
  if (attitude_period_ > 0 && step % attitude_period_ == 0) {
    log_->attitude.push_back({s.t, s.roll + attitude_error_[0] + Normal(spec_.attitude_sd_rad),
                              s.pitch + attitude_error_[1] + Normal(spec_.attitude_sd_rad),
                              s.yaw + Normal(spec_.attitude_sd_yaw_rad), spec_.attitude_sd_rad,
                              spec_.attitude_sd_rad, spec_.attitude_sd_yaw_rad});
  }
  if (pose_period_ > 0 && step % pose_period_ == 0) {
    log_->pose.push_back({s.t, s.x + Normal(spec_.pose_sd_xy_m), s.y + Normal(spec_.pose_sd_xy_m),
                          s.z + Normal(spec_.pose_sd_xy_m), s.roll + Normal(spec_.attitude_sd_rad),
                          s.pitch + Normal(spec_.attitude_sd_rad),
                          s.yaw + Normal(spec_.pose_sd_yaw_rad), spec_.pose_sd_xy_m,
                          spec_.pose_sd_xy_m, spec_.pose_sd_yaw_rad});
  }
  if (command_period_ > 0 && step % command_period_ == 0) {
    log_->commands.push_back({s.t, s.command_v_mps, s.command_yaw_rate_radps});
  }
}

void SensorSimulator::EmitImu(const KinematicState& s) {
  const double dt = imu_period_ * step_s_;
  for (int i = 0; i < 3; ++i) {
    accel_bias_[i] = GaussMarkovStep(accel_bias_[i], spec_.accel_bias_sd_mps2,
                                     spec_.accel_bias_tau_s, dt, normal_(*rng_));
    gyro_bias_[i] = GaussMarkovStep(gyro_bias_[i], spec_.gyro_bias_sd_radps, spec_.gyro_bias_tau_s,
                                    dt, normal_(*rng_));
  }
  // Specific force in the body frame: f = a - g_world expressed in body axes (REP-103, z up).
  const double cp = std::cos(s.pitch), sp = std::sin(s.pitch);
  const double cr = std::cos(s.roll), sr = std::sin(s.roll);
  // Band-limited accelerometer: the mean of dv/dt over the sample interval, so that the samples
  // integrate to the true velocity change (an instantaneous sample would alias the fast wheel and
  // tire dynamics into a velocity drift).
  const double a_x = have_previous_imu_ ? (s.v_bx - previous_v_bx_) / dt : s.a_bx;
  const double a_y = have_previous_imu_ ? (s.v_by - previous_v_by_) / dt : s.a_by;
  previous_v_bx_ = s.v_bx, previous_v_by_ = s.v_by;
  have_previous_imu_ = true;
  double f[3] = {a_x - s.v_by * s.yaw_rate - kGravity * sp,
                 a_y + s.v_bx * s.yaw_rate + kGravity * sr * cp, kGravity * cr * cp};
  f[0] += vibration_now_[0];
  f[2] += vibration_now_[1];
  double w[3] = {s.roll_rate, s.pitch_rate, s.yaw_rate};
  // imu_mounting_pitch: sensor axes pitched nose-down by delta about body y.
  const double delta = EffectValue(effects_, "imu_mounting_pitch");
  if (delta != 0.0) {
    const double cd = std::cos(delta), sd = std::sin(delta);
    const double fx = f[0] * cd - f[2] * sd, fz = f[0] * sd + f[2] * cd;
    f[0] = fx, f[2] = fz;
    const double wx = w[0] * cd - w[2] * sd, wz = w[0] * sd + w[2] * cd;
    w[0] = wx, w[2] = wz;
  }
  ImuSample imu;
  // clock_offset: the IMU's stamps are late by the offset.
  imu.t = s.t + EffectValue(effects_, "clock_offset");
  double* out_f[3] = {&imu.ax, &imu.ay, &imu.az};
  double* out_w[3] = {&imu.gx, &imu.gy, &imu.gz};
  for (int i = 0; i < 3; ++i) {
    *out_f[i] =
        f[i] + imu_errors_.accel_offset_mps2[i] + accel_bias_[i] + Normal(spec_.sd_accel_mps2);
    *out_w[i] =
        w[i] + imu_errors_.gyro_offset_radps[i] + gyro_bias_[i] + Normal(spec_.sd_gyro_radps);
  }
  log_->imu.push_back(imu);
}

double EncoderSpeedSd(const SensorSpec& spec) {
  double variance = spec.sd_omega_radps * spec.sd_omega_radps;
  if (spec.encoder_counts_per_rev > 0 && spec.wheel_rate_hz > 0.0) {
    const double q = 2.0 * M_PI / spec.encoder_counts_per_rev * spec.wheel_rate_hz;
    variance += 2.0 * q * q / 12.0;
  }
  return std::sqrt(variance);
}

void SensorSimulator::EmitWheels(const KinematicState& s) {
  const double dt = wheel_period_ * step_s_;
  WheelSample sample;
  sample.t = s.t;
  const int counts_per_rev = spec_.encoder_counts_per_rev;
  for (int w = 0; w < wheel_count_; ++w) {
    double omega = s.omega_radps[w];
    if (counts_per_rev > 0) {
      const int64_t counts =
          static_cast<int64_t>(std::floor(s.wheel_angle_rad[w] * counts_per_rev / (2.0 * M_PI)));
      omega = have_last_counts_ ? (counts - last_counts_[w]) * 2.0 * M_PI / counts_per_rev / dt
                                : s.omega_radps[w];
      last_counts_[w] = counts;
    }
    sample.omega_radps[w] = omega + Normal(spec_.sd_omega_radps);
  }
  have_last_counts_ = true;
  log_->wheels.push_back(sample);
}

void SensorSimulator::EmitGps(const KinematicState& s) {
  GpsSample gps;
  gps.t = s.t;
  gps.x = s.x + Normal(spec_.gps_sd_xy_m);
  gps.y = s.y + Normal(spec_.gps_sd_xy_m);
  gps.z = s.z + Normal(spec_.gps_sd_z_m);
  const double cy = std::cos(s.yaw), sy = std::sin(s.yaw);
  double vx = s.v_bx * cy - s.v_by * sy;
  double vy = s.v_bx * sy + s.v_by * cy;
  double vz = -s.v_bx * std::sin(s.pitch);
  const bool averaged = EffectValue(effects_, "gps_velocity_averaging") != 0.0 ||
                        spec_.mismatch.gps_velocity_interval_mean;
  if (averaged && last_gps_t_ >= 0.0) {
    // Mean velocity over the previous interval: the true position difference.
    const double dt = s.t - last_gps_t_;
    vx = (s.x - last_gps_x_) / dt;
    vy = (s.y - last_gps_y_) / dt;
    vz = (s.z - last_gps_z_) / dt;
  }
  last_gps_x_ = s.x, last_gps_y_ = s.y, last_gps_z_ = s.z, last_gps_t_ = s.t;
  gps.vx = vx + Normal(spec_.gps_sd_v_mps);
  gps.vy = vy + Normal(spec_.gps_sd_v_mps);
  gps.vz = vz + Normal(spec_.gps_sd_v_mps);
  gps.sd_xy = spec_.gps_sd_xy_m;
  gps.sd_z = spec_.gps_sd_z_m;
  gps.sd_v = spec_.gps_sd_v_mps;
  log_->gps.push_back(gps);
}

}  // namespace sim
}  // namespace slipgraph
