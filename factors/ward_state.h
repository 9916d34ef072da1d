// State layout and parameters of the Ward & Iagnemma longitudinal model.
//
// State x (7), Ward & Iagnemma Sec. III-B:
//   x[kVbx]        v_bx      body-x velocity over ground, m/s
//   x[kAccelBias]  b_ax      accelerometer x walking bias, m/s^2
//   x[kAdist]      a_dist    disturbance acceleration along body x, m/s^2 (resistive < 0 forward)
//   x[kOmegaLeft]  w_l       left driven wheel (or side) angular velocity, rad/s
//   x[kOmegaRight] w_r       right driven wheel (or side) angular velocity, rad/s
//   x[kYawRate]    yaw_rate  body yaw rate, rad/s, counter-clockwise positive (REP-103)
//   x[kGyroBias]   b_gz      yaw gyro walking bias, rad/s
//
// Wheel sets: diff_drive_castor has two driven front wheels (left, right). skid_steer's left and
// right are its two tracks/sides. rocker_bogie6's six wheels are driven together per side: the
// side speed is the mean of its three wheel speeds (io/measurement_stream does the mapping).
#pragma once

#include "model/model_config.h"
#include "model/vehicle.h"

namespace slipgraph {

// How v_bx is propagated. kTireDynamics is eq. (10) as printed: v' = f_tire + a_dist - g sin(phi),
// the accelerometer an eq. (11) measurement. kAccelerometerDriven integrates the accelerometer
// (v' = a_x - c_ax - b_ax - g sin(phi), the strapdown form) and keeps eq. (11) as the measurement
// that ties a_dist to the tire model, with the tire law's own uncertainty in its noise. The two are
// the same equations; they differ in where the noise is. With a stiff tire law (d v'/d v of
// order -100 1/s) and tire coefficients off by tens of percent, the first slaves v_bx to r w and
// misses slow hold-backs (docs/ekf.md); the second keeps the accelerometer's integral.
enum class VelocityModel { kTireDynamics, kAccelerometerDriven };

namespace ward {

enum StateIndex : int {
  kVbx = 0,
  kAccelBias = 1,
  kAdist = 2,
  kOmegaLeft = 3,
  kOmegaRight = 4,
  kYawRate = 5,
  kGyroBias = 6,
};
constexpr int kStateSize = 7;

// Everything the physics needs, gathered once from the vehicle and the model configuration.
struct Params {
  VehicleType type = VehicleType::kDiffDriveCastor;
  double mass_kg = 1.0;
  double yaw_inertia_kgm2 = 1.0;
  double wheel_radius_m = 0.1;
  double track_width_m = 0.5;
  double cg_to_front_m = 0.3;
  double cg_to_rear_m = 0.3;
  double cg_height_m = 0.3;
  double gravity_mps2 = 9.80665;
  TireParams tire;
  RollingParams rolling;
  double accel_bias_tau_s = 300.0;
  double gyro_bias_tau_s = 300.0;
};

inline Params MakeParams(const Vehicle& vehicle, const ModelConfig& model) {
  Params p;
  p.type = vehicle.type;
  p.mass_kg = vehicle.mass_kg;
  p.yaw_inertia_kgm2 = vehicle.yaw_inertia_kgm2;
  p.wheel_radius_m = vehicle.wheel_radius_m;
  p.track_width_m = vehicle.track_width_m;
  p.cg_to_front_m = vehicle.cg_to_front_m;
  p.cg_to_rear_m = vehicle.cg_to_rear_m;
  p.cg_height_m = vehicle.cg_height_m;
  p.gravity_mps2 = model.gravity_mps2;
  p.tire = model.tire;
  p.rolling = model.rolling;
  p.accel_bias_tau_s = model.process.accel_bias_tau_s;
  p.gyro_bias_tau_s = model.process.gyro_bias_tau_s;
  return p;
}

// Terrain attitude under the vehicle, REP-103 angles (inputs, not states).
template <typename T>
struct Attitude {
  T roll_rad;
  T pitch_rad;  // REP-103: nose down positive
};

}  // namespace ward
}  // namespace slipgraph
