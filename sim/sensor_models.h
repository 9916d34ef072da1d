// Sensor models shared by the vehicle simulators: IMU with constant offsets, walking biases and
// white noise; quantized wheel encoders; GNSS position/velocity; attitude; reference pose;
// commands. They turn the true motion into the rows of a drive log, applying the sensor-side
// effects (imu_mounting_pitch, clock_offset, gps_velocity_averaging).
#pragma once

#include <array>
#include <cstdint>
#include <random>

#include "io/drive_log.h"
#include "sim/random.h"
#include "sim/scenario.h"

namespace slipgraph {
namespace sim {

// True motion at one instant, log frames (REP-103 body, ENU world).
struct KinematicState {
  double t = 0.0;
  double x = 0.0, y = 0.0, z = 0.0;
  double roll = 0.0, pitch = 0.0, yaw = 0.0;  // pitch positive nose down
  double roll_rate = 0.0, pitch_rate = 0.0;
  double v_bx = 0.0, v_by = 0.0, yaw_rate = 0.0;
  double a_bx = 0.0;  // dv_bx/dt (instantaneous; the IMU model band-limits it)
  double a_by = 0.0;  // dv_by/dt
  std::array<double, kMaxWheels> wheel_angle_rad{};
  std::array<double, kMaxWheels> omega_radps{};
  double command_v_mps = 0.0;
  double command_yaw_rate_radps = 0.0;
};

// Constant IMU offsets drawn for a run, recorded in sim.yaml.
struct ImuErrors {
  double accel_offset_mps2[3] = {0.0, 0.0, 0.0};
  double gyro_offset_radps[3] = {0.0, 0.0, 0.0};
};

// The sd of one simulated encoder speed sample: the white noise and the quantization of a count
// difference over one wheel period (two independent uniform rounding errors of one count each,
// variance 2 q^2 / 12 with q the speed of one count per period).
double EncoderSpeedSd(const SensorSpec& spec);

class SensorSimulator {
 public:
  // `step_s` is the simulator's integration step: every rate must be a whole number of steps.
  SensorSimulator(const SensorSpec& spec, const EffectSet& effects, int wheel_count, double step_s,
                  std::mt19937_64* rng, DriveLog* log);

  // Called once per integration step, step_index counting from 0 at t = 0.
  void Observe(const KinematicState& state, int64_t step_index);

  const ImuErrors& imu_errors() const { return imu_errors_; }

 private:
  int64_t Period(double rate_hz) const;  // in steps; 0 when the stream is off
  void EmitImu(const KinematicState& s);
  void EmitWheels(const KinematicState& s);
  void EmitGps(const KinematicState& s);
  // The mismatch suites' sensor errors (SensorSpec::mismatch), stepped with the simulation.
  void StepMismatch(const KinematicState& s);
  double Normal(double sd);

  SensorSpec spec_;
  EffectSet effects_;
  int wheel_count_;
  double step_s_;
  std::mt19937_64* rng_;
  UnitNormal normal_;
  DriveLog* log_;
  ImuErrors imu_errors_;
  double accel_bias_[3] = {0.0, 0.0, 0.0};
  // Body velocity at the previous IMU sample: the accelerometer reports the mean acceleration
  // over its sample interval (an anti-aliased MEMS output), i.e. the velocity change / interval.
  double previous_v_bx_ = 0.0, previous_v_by_ = 0.0;
  bool have_previous_imu_ = false;
  double gyro_bias_[3] = {0.0, 0.0, 0.0};
  // Chassis vibration along x and z: unit-variance resonances z_k (AR(2), the last two values
  // each), scaled by |v| on output.
  double vibration_[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  double vibration_a1_ = 0.0, vibration_a2_ = 0.0, vibration_gain_ = 0.0;
  double attitude_error_[2] = {0.0, 0.0};  // roll, pitch (Gauss-Markov)
  double vibration_now_[2] = {0.0, 0.0};   // m/s^2 along x and z
  std::array<int64_t, kMaxWheels> last_counts_{};
  bool have_last_counts_ = false;
  double last_gps_x_ = 0.0, last_gps_y_ = 0.0, last_gps_z_ = 0.0, last_gps_t_ = -1.0;
  int64_t imu_period_, wheel_period_, gps_period_, attitude_period_, pose_period_, command_period_;
};

}  // namespace sim
}  // namespace slipgraph
