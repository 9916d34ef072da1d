#include "solvers/ward_ekf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "factors/ward_dynamics.h"
#include "model/option_check.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state and measurement indices

bool IsFinite(double value) { return std::isfinite(value); }

}  // namespace

bool EkfOptions::IsValid(std::string* error) const {
  const double min_initial_sd = *std::min_element(initial_sd.begin(), initial_sd.end());
  return OptionCheck("EkfOptions", error)
      .Positive("wheels_gate_chi2", wheels_gate_chi2)
      .Positive("gps_gate_chi2", gps_gate_chi2)
      .Positive("imu_gate_chi2", imu_gate_chi2)
      .NonNegative("imu_max_consecutive_rejections", imu_max_consecutive_rejections)
      .NonNegative("wheels_max_consecutive_rejections", wheels_max_consecutive_rejections)
      .NonNegative("gps_max_consecutive_rejections", gps_max_consecutive_rejections)
      .Positive("encoder_timeout_s", encoder_timeout_s)
      .Positive("wheel_still_radps", wheel_still_radps)
      .Require("initial_sd", min_initial_sd > 0.0, min_initial_sd, "each entry must be positive")
      .Require("gnss_fading_fixes", gnss_fading_fixes == 0.0 || gnss_fading_fixes >= 1.0,
               gnss_fading_fixes, "must be 0 (off) or at least 1")
      .Positive("gnss_fading_threshold", gnss_fading_threshold)
      .AtLeast("gnss_fading_max", gnss_fading_max, 1.0);
}

WardEkf::WardEkf(const Vehicle& vehicle, const ModelConfig& model, const EkfOptions& options)
    : propagator_(model.process, model.measurement.imu_sd_accel_mps2),
      gnss_fading_(options.gnss_fading_fixes, options.gnss_fading_threshold,
                   options.gnss_fading_max, options.gps_gate_chi2),
      slip_persistence_(model.slip_persistence),
      params_(MakeParams(vehicle, model)),
      model_(model),
      options_(options),
      offsets_(model.offset_init_samples, model.offset_ema_samples, model.offset_rest_guard_s,
               vehicle.type == VehicleType::kSkidSteer ? 1.0 : 0.2),
      detector_(model.immobilization, vehicle.wheel_radius_m, vehicle.track_width_m),
      rest_timer_(model.weak_constraints.still_smoothing_s, options.wheel_still_radps) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  for (int i = 0; i < kStateSize; ++i) P_(i, i) = options.initial_sd[i] * options.initial_sd[i];
  loads_ = ComputeAttitudeLoads(CurrentAttitude(), params_);
  imu_gate_ = {options.imu_gate_chi2, options.imu_max_consecutive_rejections};
  wheels_gate_ = {options.wheels_gate_chi2, options.wheels_max_consecutive_rejections};
  gps_gate_ = {options.gps_gate_chi2, options.gps_max_consecutive_rejections};
}

void WardEkf::Begin(double t) {
  if (!started_) {
    started_ = true;
    t_ = t;
    return;
  }
  if (t < t_) {
    ++stats_.late_measurements;
    return;
  }
  PredictTo(t);
}

void WardEkf::PredictTo(double t) {
  const double dt = t - t_;
  if (dt <= 0.0) return;
  PropagationInput input;
  input.accelerometer_driven =
      options_.velocity_model == VelocityModel::kAccelerometerDriven && have_accel_input_;
  input.accel_input_mps2 = accel_input_mps2_ - offsets_.accel_x_mps2();
  input.pitch_sd_rad = pitch_sd_rad_;
  input.imu_period_s = imu_period_s_;
  const double v_bx_before = x_(kVbx), b_ax_before = x_(kAccelBias);
  propagator_.Predict(dt, input, loads_, params_, &x_, &P_);
  if (input.accelerometer_driven) {
    const double removed_bias_mps2 = offsets_.accel_x_mps2() + 0.5 * (b_ax_before + x_(kAccelBias));
    slip_persistence_.AddFeltVelocityChange(x_(kVbx) - v_bx_before, removed_bias_mps2 * dt);
  }
  t_ = t;
}

bool WardEkf::Update(const ekf::MeasurementRows& rows, StreamGate* gate, StreamCounters* counters) {
  const int m = rows.size();
  if (m == 0) return false;
  const bool score = (options_.track_log_likelihood || scoring_) && gate != nullptr;
  if (gate != nullptr && !std::isinf(gate->chi2)) {
    const ekf::InnovationDistance d = ekf::DistanceOf(rows, P_);
    if (d.mahalanobis > gate->chi2) {
      if (++gate->consecutive_rejections <= gate->max_consecutive_rejections) {
        ++counters->rejected;
        if (options_.record_innovations && m == 1 && rows.name(0) != nullptr) {
          // One row: the gate's distance is nu^2 / s (positive past the gate).
          const double nu = rows.innovation(0);
          EkfStats::InnovationSeries& series = stats_.innovations[rows.name(0)];
          series.gated_t.push_back(t_);
          series.gated_normalized.push_back(std::copysign(std::sqrt(d.mahalanobis), nu));
          series.gated_measurement_share.push_back(rows.variance(0) * d.mahalanobis / (nu * nu));
        }
        // A measurement gated out still happened: it counts against the model in the likelihood.
        if (score) log_likelihood_ += d.LogLikelihood(m);
        return false;
      }
      ++counters->forced;
    }
  }
  if (gate != nullptr) gate->consecutive_rejections = 0;
  double normalized[ekf::kMaxRows], share[ekf::kMaxRows];
  const bool record = options_.record_innovations;
  log_likelihood_ += ekf::ApplySequentialUpdate(
      rows, score, &x_, &P_, record ? normalized : nullptr, record ? share : nullptr);
  if (record) {
    for (int i = 0; i < m; ++i) {
      if (rows.name(i) == nullptr) continue;
      EkfStats::InnovationSeries& series = stats_.innovations[rows.name(i)];
      series.t.push_back(t_);
      series.normalized.push_back(normalized[i]);
      series.measurement_share.push_back(share[i]);
    }
  }
  ++counters->used;
  return true;
}

void WardEkf::GuardDivergence() {
  // No state of a ground robot (m/s, m/s^2, rad/s) comes near this: beyond it the filter has
  // diverged even while its numbers are still finite (an unstable yaw step grows ~10x per step).
  constexpr double kDivergedMagnitude = 1e6;
  if (x_.allFinite() && P_.allFinite() && x_.cwiseAbs().maxCoeff() < kDivergedMagnitude) {
    last_good_x_ = x_;
    last_good_P_ = P_;
    return;
  }
  if (stats_.divergence_resets++ == 0) stats_.first_divergence_t = t_;
  x_ = last_good_x_;
  P_ = last_good_P_ * 100.0;
}

void WardEkf::AddAttitude(const AttitudeSample& attitude) {
  if (!IsFinite(attitude.roll) || !IsFinite(attitude.pitch)) {
    ++stats_.attitude.dropped_components;
    return;
  }
  roll_rad_ = attitude.roll;
  pitch_rad_ = attitude.pitch;
  loads_ = ComputeAttitudeLoads(CurrentAttitude(), params_);
  pitch_sd_rad_ = std::isfinite(attitude.sd_pitch) ? attitude.sd_pitch : 0.0;
  if (IsFinite(attitude.yaw)) yaw_rad_ = attitude.yaw, have_yaw_ = true;
  have_attitude_ = true;
  ++stats_.attitude.used;
}

void WardEkf::AddImu(const ImuSample& imu) {
  struct Guard {
    WardEkf* ekf;
    ~Guard() { ekf->GuardDivergence(); }
  } guard{this};
  // The prediction up to this stamp is driven by the previous accelerometer sample (held): on
  // the simulated suites this did better than driving it with this sample, although this one is
  // the mean over exactly that interval (docs/ekf.md).
  Begin(imu.t);
  if (offsets_.ready() && std::isfinite(imu.ax)) {
    accel_input_mps2_ = imu.ax;
    have_accel_input_ = true;
  }
  if (last_imu_t_ >= 0.0 && imu.t > last_imu_t_) {
    imu_period_s_ += 0.05 * (imu.t - last_imu_t_ - imu_period_s_);  // slow average
  }
  last_imu_t_ = imu.t;
  const bool at_rest = stop_timer_.AtRestFor(t_, model_.weak_constraints.stop_time_s);
  const bool ax_ok = IsFinite(imu.ax), gz_ok = IsFinite(imu.gz);
  if (!offsets_.ready()) {
    if (ax_ok && gz_ok) {
      offsets_.Add(imu.t, imu.ax, imu.gz, loads_.gravity_along_x_mps2, at_rest, last_wheel_motion_);
      ++stats_.offset_init_samples;
      if (offsets_.ready() && offsets_.moving_start()) {
        stats_.offset_moving_start = true;
        stats_.offset_implausible_start = offsets_.implausible_start();
        P_(kAccelBias, kAccelBias) += offsets_.init_sd()[0] * offsets_.init_sd()[0];
        P_(kGyroBias, kGyroBias) += offsets_.init_sd()[1] * offsets_.init_sd()[1];
      }
    }
    return;
  }
  if (ax_ok && gz_ok) offsets_.Add(imu.t, imu.ax, imu.gz, loads_.gravity_along_x_mps2, at_rest);
  stats_.imu.dropped_components += (ax_ok ? 0 : 1) + (gz_ok ? 0 : 1);

  const ekf::MeasurementRows rows =
      ImuRows(x_, imu, loads_, ImuOffsets<double>{offsets_.accel_x_mps2(), offsets_.gyro_z_radps()},
              params_, model_, options_.velocity_model == VelocityModel::kAccelerometerDriven,
              imu_period_s_);
  if (ax_ok) {
    // Normalized innovation squared of the accelerometer alone, for the adaptive w3.
    const double s = rows.jacobian(0) * P_ * rows.jacobian(0).transpose() + rows.variance(0);
    propagator_.ObserveAccelerometerNis(rows.innovation(0) * rows.innovation(0) / s);
  }
  Update(rows, &imu_gate_, &stats_.imu);
}

void WardEkf::AddWheels(double t, double omega_left, double omega_right) {
  struct Guard {
    WardEkf* ekf;
    ~Guard() { ekf->GuardDivergence(); }
  } guard{this};
  const bool left_ok = IsFinite(omega_left), right_ok = IsFinite(omega_right);
  if (!wheels_initialised_ && left_ok && right_ok) {
    if (!started_) Begin(t);
    x_(kOmegaLeft) = omega_left;
    x_(kOmegaRight) = omega_right;
    wheels_initialised_ = true;
    if (!BothWheelsStill(omega_left, omega_right, options_.wheel_still_radps)) {
      // A log that starts in motion: the body moves as its wheels roll, give or take a slip of
      // up to a fifth (not the rest the initial state assumes).
      const double r = params_.wheel_radius_m;
      x_(kVbx) = 0.5 * r * (omega_left + omega_right);
      x_(kYawRate) = r * (omega_right - omega_left) / params_.track_width_m;
      P_(kVbx, kVbx) = std::max(P_(kVbx, kVbx), std::pow(0.2 * x_(kVbx), 2));
      P_(kYawRate, kYawRate) = std::max(P_(kYawRate, kYawRate), std::pow(0.3 * x_(kYawRate), 2));
    }
  }
  Begin(t);
  stats_.wheels.dropped_components += (left_ok ? 0 : 1) + (right_ok ? 0 : 1);
  Update(WheelRows(x_, omega_left, omega_right, model_.measurement.wheels_sd_omega_radps),
         &wheels_gate_, &stats_.wheels);

  if (left_ok && right_ok) {
    last_wheels_t_ = t_;
    rest_timer_.Update(t_, omega_left, omega_right);
    const bool still = rest_timer_.reading_still();
    const EncoderMotion motion =
        EncoderMotionOf(omega_left, omega_right, params_.wheel_radius_m, params_.track_width_m);
    last_wheel_motion_ = {motion.speed_mps, motion.yaw_rate_radps, still};
    stop_timer_.Update(t_, still);
  }
  const double dt_cycle = have_previous_cycle_ ? t_ - t_previous_cycle_ : 0.0;
  if (offsets_.ready()) ApplyWeakConstraints(dt_cycle);
  if (offsets_.ready() && left_ok && right_ok) CheckBiasAgainstWheels();
  const bool fresh = t_ - last_wheels_t_ <= options_.encoder_timeout_s;
  previous_slip_ema_ = detector_.latest().slip_ema;
  detector_.Update(x_(kVbx), x_(kYawRate), x_(kOmegaLeft), x_(kOmegaRight), fresh,
                   std::sqrt(std::max(0.0, P_(kVbx, kVbx))));
  x_previous_cycle_ = x_;
  t_previous_cycle_ = t_;
  have_previous_cycle_ = true;
}

void WardEkf::ApplyWeakConstraints(double dt_cycle) {
  WeakConstraintInputs in;
  in.dt_s = dt_cycle;
  in.vel_dir = DriveDirection(x_(kOmegaLeft), x_(kOmegaRight), options_.wheel_still_radps);
  in.slip_ema = detector_.latest().slip_ema;
  in.slip_ema_rate_per_s =
      dt_cycle > 0.0 ? (detector_.latest().slip_ema - previous_slip_ema_) / dt_cycle : 0.0;
  in.wheels_stopped_s = rest_timer_.StoppedFor(t_);
  if (MovingAgainstTheWheels(x_.data(), in.vel_dir)) {  // WC3 alone reads it
    // Read at the a priori v_bx, the rolling law would make the "holding" disturbance 0.35 m/s^2
    // too strong (fig5).
    in.f_tire_mps2 = HeldStillTireForce(x_.data(), loads_, params_);
  }
  in.gravity_along_x_mps2 = loads_.gravity_along_x_mps2;
  pseudo_.clear();
  const StateVector x_prior = x_;
  CollectWeakConstraints(x_prior.data(), x_previous_cycle_.data(), in, model_.weak_constraints,
                         &pseudo_);
  // Densities to per-cycle variances (the first cycle uses the nominal 100 Hz).
  const double cycle_s = dt_cycle > 0.0 ? dt_cycle : 0.01;
  StreamCounters unused;
  for (const PseudoMeasurement& p : pseudo_) {
    ekf::MeasurementRows row;
    row.AddOnState(p.state_index, p.z - x_(p.state_index), p.density * p.density / cycle_s);
    Update(row, nullptr, &unused);
    ++stats_.weak_constraints[static_cast<int>(p.constraint)];
  }
}

void WardEkf::CheckBiasAgainstWheels() {
  if (!slip_persistence_.enabled() ||
      options_.velocity_model != VelocityModel::kAccelerometerDriven || !have_accel_input_) {
    return;
  }
  SlipPersistence::CycleInput in;
  in.t_s = t_;
  in.rim_speed_mps = 0.5 * params_.wheel_radius_m * (x_(kOmegaLeft) + x_(kOmegaRight));
  in.v_bx_mps = x_(kVbx);
  in.bias_variance_mps2_sq = P_(kAccelBias, kAccelBias);
  SlipPersistence::Measurement m;
  switch (slip_persistence_.Cycle(in, &m)) {
    case SlipPersistence::Outcome::kMeasured: {
      ekf::MeasurementRows row;
      row.AddOnState(kAccelBias, m.innovation_mps2, m.variance_mps2_sq, "slip_persistence");
      stats_.wheel_bias_checks.push_back(
          {t_, m.removed_bias_mps2 + m.innovation_mps2, std::sqrt(m.variance_mps2_sq)});
      const double v_bx_before_mps = x_(kVbx);
      Update(row, nullptr, &stats_.slip_persistence);
      if (m.velocity_variance_mps_sq > 0.0) {
        // Against the state the bias row left: through their correlation it moved v_bx too.
        // (The run's last interval is in both rows; the noise they share is not modelled.)
        ekf::MeasurementRows velocity;
        velocity.AddOnState(kVbx, m.velocity_innovation_mps - (x_(kVbx) - v_bx_before_mps),
                            m.velocity_variance_mps_sq, "slip_persistence_velocity");
        StreamCounters part_of_the_check;
        Update(velocity, nullptr, &part_of_the_check);
        ++stats_.slip_persistence_lasting;
      }
      break;
    }
    case SlipPersistence::Outcome::kLeftOut:
      ++stats_.slip_persistence.rejected;
      break;
    case SlipPersistence::Outcome::kNone:
      break;
  }
}

double WardEkf::AddGpsScored(const GpsSample& gps) {
  const double sum_before = log_likelihood_;
  log_likelihood_ = 0.0;
  scoring_ = true;
  AddGps(gps);
  scoring_ = false;
  const double fix = log_likelihood_;
  log_likelihood_ = sum_before + (options_.track_log_likelihood ? fix : 0.0);
  return fix;
}

void WardEkf::AddGps(const GpsSample& gps) {
  struct Guard {
    WardEkf* ekf;
    ~Guard() { ekf->GuardDivergence(); }
  } guard{this};
  Begin(gps.t);
  if (!IsFinite(gps.vx) || !IsFinite(gps.vy) || !IsFinite(gps.vz)) {
    ++stats_.gps.dropped_components;
    return;
  }
  // The yaw corrected by the course of the fixes before this one; then this fix read, with the
  // latest encoder reading, as io/gnss_heading_offsets.h reads a whole log.
  const double heading_offset_rad =
      model_.gnss_heading_from_course ? gnss_heading_.offset_rad() : 0.0;
  if (heading_offset_rad != 0.0) {
    stats_.gnss_heading_offset_rad = heading_offset_rad;
    ++stats_.gnss_heading_corrected;
  }
  const ekf::MeasurementRows rows =
      GnssRows(x_, gps, {have_attitude_, pitch_rad_, yaw_rad_ + heading_offset_rad},
               model_.measurement.gps_sd_v_mps);
  if (have_yaw_ && t_ - last_wheels_t_ <= gnss_heading_.options().max_wheel_age_s) {
    gnss_heading_.Observe(gps.vx, gps.vy, GnssVelocitySd(gps, model_.measurement.gps_sd_v_mps),
                          yaw_rad_, last_wheel_motion_.speed_mps,
                          last_wheel_motion_.yaw_rate_radps);
  }
  // Fading memory (EkfOptions::gnss_fading_*): not in a bank of laws, whose weights are each
  // fix's likelihood under the filter's own covariance (AddGpsScored).
  if (options_.gnss_fading_fixes > 0.0 && !scoring_) {
    const bool gate_lets_in =
        gps_gate_.consecutive_rejections >= gps_gate_.max_consecutive_rejections;
    const double scale =
        gnss_fading_.ScaleFor(rows.innovation(0), P_(kVbx, kVbx) + rows.variance(0), gate_lets_in);
    if (scale != 1.0) {
      P_ *= scale;
      ++stats_.gnss_fading;
    }
  }
  Update(rows, &gps_gate_, &stats_.gps);
}

WardEstimate WardEkf::Estimate() const {
  WardEstimate e;
  e.t = t_;
  for (int i = 0; i < kStateSize; ++i) {
    e.x[i] = x_(i);
    e.sd[i] = std::sqrt(std::max(0.0, P_(i, i)));
  }
  e.slip = detector_.latest();
  // Missing encoder data is never reported as immobilization.
  if (t_ - last_wheels_t_ > options_.encoder_timeout_s) e.slip.immobilized = false;
  e.accel_offset_mps2 = offsets_.accel_x_mps2();
  e.gyro_offset_radps = offsets_.gyro_z_radps();
  e.offsets_ready = offsets_.ready();
  return e;
}

}  // namespace slipgraph
