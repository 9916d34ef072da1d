#include "model/model_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "model/effect_catalogue.h"

namespace slipgraph {
namespace {

// Appends "name must be positive (value)" when value <= 0 or not finite.
bool CheckPositive(const char* name, double value, std::string* error) {
  if (std::isfinite(value) && value > 0.0) return true;
  std::ostringstream message;
  message << name << " must be positive and finite (got " << value << ")";
  *error = message.str();
  return false;
}

}  // namespace

bool SlipPersistenceConfig::IsValid(std::string* error) const {
  if (!(interval_s >= 0.0 && std::isfinite(interval_s))) {
    *error = "slip_persistence.interval must be finite and non-negative (0: off)";
    return false;
  }
  if (interval_s == 0.0) return true;
  const struct {
    const char* name;
    double value;
  } positive[] = {{"slip_persistence.sd", sd_mps},
                  {"slip_persistence.gate", gate_sd},
                  {"slip_persistence.smoothing", smoothing_s},
                  {"slip_persistence.min_rim_speed", min_rim_speed_mps},
                  {"slip_persistence.max_rim_acceleration", max_rim_acceleration_mps2},
                  {"slip_persistence.max_lasting_error", max_lasting_error_mps2}};
  for (const auto& field : positive) {
    if (!CheckPositive(field.name, field.value, error)) return false;
  }
  if (lasting_intervals < 0) {
    *error = "slip_persistence.lasting_intervals must be non-negative (0: off)";
    return false;
  }
  return true;
}

bool ModelConfig::IsValid(std::string* error) const {
  const struct {
    const char* name;
    double value;
  } positive[] = {
      {"gravity", gravity_mps2},
      {"tire.C1", tire.C1},
      {"tire.At", tire.At},
      {"rolling.A_roll", rolling.A_roll},
      {"process.v_bx", process.v_bx_mps2_per_sqrt_hz},
      {"process.a_dist", process.a_dist_mps3_per_sqrt_hz},
      {"process.a_dist_max", process.a_dist_max_mps3_per_sqrt_hz},
      {"process.a_dist_adapt_samples", process.a_dist_adapt_samples},
      {"process.omega", process.omega_radps2_per_sqrt_hz},
      {"process.yaw_rate", process.yaw_rate_radps2_per_sqrt_hz},
      {"process.accel_bias_sd", process.accel_bias_sd_mps2},
      {"process.accel_bias_tau", process.accel_bias_tau_s},
      {"process.gyro_bias_sd", process.gyro_bias_sd_radps},
      {"process.gyro_bias_tau", process.gyro_bias_tau_s},
      {"measurement.imu_sd_accel", measurement.imu_sd_accel_mps2},
      {"measurement.imu_sd_gyro", measurement.imu_sd_gyro_radps},
      {"measurement.wheels_sd_omega", measurement.wheels_sd_omega_radps},
      {"measurement.gps_sd_v", measurement.gps_sd_v_mps},
      {"measurement.gps_sd_xy", measurement.gps_sd_xy_m},
      {"weak_constraints.sd_oppose_motion", weak_constraints.sd_oppose_motion},
      {"weak_constraints.sd_act_quickly", weak_constraints.sd_act_quickly},
      {"weak_constraints.sd_no_pull_back", weak_constraints.sd_no_pull_back},
      {"weak_constraints.sd_at_rest", weak_constraints.sd_at_rest},
      {"weak_constraints.sd_bound", weak_constraints.sd_bound},
      {"weak_constraints.stop_time", weak_constraints.stop_time_s},
      {"weak_constraints.max_v_bx", weak_constraints.max_v_bx_mps},
      {"weak_constraints.max_accel_bias", weak_constraints.max_accel_bias_mps2},
      {"weak_constraints.max_a_dist", weak_constraints.max_a_dist_mps2},
      {"weak_constraints.max_gyro_bias", weak_constraints.max_gyro_bias_radps},
      {"weak_constraints.max_v_bx_rate", weak_constraints.max_v_bx_rate_mps2},
      {"weak_constraints.max_accel_bias_rate", weak_constraints.max_accel_bias_rate_mps3},
      {"immobilization.ema_samples", immobilization.ema_samples},
      {"immobilization.slip_threshold", immobilization.slip_threshold},
      {"immobilization.low_speed", immobilization.low_speed_mps},
      {"immobilization.min_wheel_speed", immobilization.min_wheel_speed_mps},
      {"offset_ema_samples", offset_ema_samples},
      {"tire_uncertainty.relative_sd", tire_uncertainty.relative_sd},
      {"tire_uncertainty.floor", tire_uncertainty.floor_mps2},
  };
  for (const auto& field : positive) {
    if (!CheckPositive(field.name, field.value, error)) return false;
  }
  for (double scale : {calibration.wheel_radius_scale_left, calibration.wheel_radius_scale_right}) {
    if (!(scale >= 0.5 && scale <= 2.0)) {
      *error = "calibration.wheel_radius_scale_left and _right must be within [0.5, 2]";
      return false;
    }
  }
  if (!(std::abs(calibration.imu_time_offset_s) <= 1.0)) {
    *error = "calibration.imu_time_offset must be within [-1, 1] s";
    return false;
  }
  if (!(std::abs(calibration.wheels_time_offset_s) <= 1.0)) {
    *error = "calibration.wheels_time_offset must be within [-1, 1] s";
    return false;
  }
  if (!(std::abs(calibration.imu_mounting_pitch_rad) <= kMaxImuMountingPitchRad)) {
    *error = "calibration.imu_mounting_pitch must be within [-0.2, 0.2] rad";
    return false;
  }
  if (!(calibration.track_width_m >= 0.0)) {
    *error = "calibration.track_width must be non-negative (0: vehicle.yaml's)";
    return false;
  }
  if (!(immobilization.velocity_sd_margin >= 0.0 &&
        std::isfinite(immobilization.velocity_sd_margin))) {
    *error = "immobilization.velocity_sd_margin must be finite and non-negative (0: off)";
    return false;
  }
  if (!(process.attitude_error_walk_s >= 0.0 && std::isfinite(process.attitude_error_walk_s))) {
    *error = "process.attitude_error_walk must be finite and non-negative (0: off)";
    return false;
  }
  if (!slip_persistence.IsValid(error)) return false;
  if (!(process.a_dist_decay_tau_s >= 0.0)) {
    *error = "process.a_dist_decay_tau must be non-negative (0: a random walk)";
    return false;
  }
  if (tire_uncertainty.slip_relative_sd < 0.0 || tire_uncertainty.slip_floor_mps < 0.0) {
    *error = "tire_uncertainty.slip_relative_sd and slip_floor must be non-negative";
    return false;
  }
  for (double sd :
       {tire_sd.C1, tire_sd.At, tire_sd.C2, rolling_sd.R1, rolling_sd.A_roll, rolling_sd.R2}) {
    if (!(sd >= 0.0)) {
      *error = "tire_sd and rolling_sd must be non-negative";
      return false;
    }
  }
  if (!(tire_slip_stiffness_relative_sd >= 0.0 &&
        tire_slip_stiffness_relative_sd <= kMaxSlipStiffnessRelativeSd)) {
    *error = "tire_sd.slip_stiffness " + std::to_string(tire_slip_stiffness_relative_sd) +
             " must lie in [0, 2] (the sd of the log of the law's slope)";
    return false;
  }
  for (size_t i = 0; i < law_samples.size(); ++i) {
    const LawSample& soil = law_samples[i];
    if (!(soil.tire.C1 > 0.0 && soil.tire.At > 0.0 && soil.rolling.A_roll > 0.0 &&
          soil.rolling.R1 >= 0.0 && soil.rolling.R2 >= 0.0)) {
      *error = "law_samples[" + std::to_string(i) +
               "]: C1, At and A_roll must be positive, R1 and R2 non-negative";
      return false;
    }
  }
  if (rolling.R1 < 0.0 || rolling.R2 < 0.0) {
    *error = "rolling.R1 and rolling.R2 must be non-negative";
    return false;
  }
  if (!(weak_constraints.oppose_motion_cauchy_scale_mps2 >= 0.0)) {
    *error = "weak_constraints.oppose_motion_cauchy_scale must be non-negative (0: the paper's)";
    return false;
  }
  if (!(weak_constraints.still_smoothing_s >= 0.0 &&
        std::isfinite(weak_constraints.still_smoothing_s))) {
    *error =
        "weak_constraints.still_smoothing must be finite and non-negative (0: the paper's test)";
    return false;
  }
  if (!(weak_constraints.decay_alpha > 0.0 && weak_constraints.decay_alpha < 1.0)) {
    *error = "weak_constraints.decay_alpha must lie in (0, 1)";
    return false;
  }
  for (const EffectWindow& w : effect_windows) {
    if (!(std::isfinite(w.t_start_s) && std::isfinite(w.t_end_s) && w.t_end_s > w.t_start_s)) {
      *error = "effect_windows: a window must have finite from < to";
      return false;
    }
  }
  if (!(offset_rest_guard_s >= 0.0)) {
    *error = "offsets.rest_guard must be non-negative";
    return false;
  }
  if (offset_init_samples < 1) {
    *error = "offset_init_samples must be at least 1";
    return false;
  }
  return true;
}

bool ModelConfig::InEffectWindow(const std::string& effect, double t) const {
  return std::any_of(effect_windows.begin(), effect_windows.end(), [&](const EffectWindow& w) {
    return w.effect == effect && t >= w.t_start_s && t < w.t_end_s;
  });
}

void UsePapersAccelBias(ModelConfig* model) {
  model->process.attitude_error_walk_s = 0.0;
  model->slip_persistence.interval_s = 0.0;
}

ModelConfig DefaultModelConfig(const Vehicle& vehicle) {
  ModelConfig config;
  config.tire = vehicle.tire;
  config.rolling = vehicle.rolling;
  config.tire_sd = vehicle.tire_sd;
  config.rolling_sd = vehicle.rolling_sd;
  config.law_samples = vehicle.law_samples;
  config.measurement = vehicle.sensors;
  return config;
}

}  // namespace slipgraph
