// The EKF's prediction: eq. (10) over dt by the shared RK4 step (factors/ward_dynamics.h),
// accelerometer-driven when an accelerometer input is held (its transition matrix by the chain
// rule through the stages, factors/ward_accel_driven_step.h) and the paper's form otherwise (a
// Jet pass), then the discrete process noise: white densities times dt, the biases' exact
// Gauss-Markov variance (b_ax's with a walk for the attitude's slow error through gravity when
// the accelerometer drives), and the disturbance's density w3 scaled by the accelerometer's recent
// normalized innovation squared (the adaptive w3).
#pragma once

#include "factors/ward_dynamics.h"
#include "factors/ward_state.h"
#include "model/model_config.h"
#include "solvers/ekf_update.h"

namespace slipgraph {

// What the prediction takes from the measurements besides the state.
struct PropagationInput {
  // The held accelerometer x reading less its offset (m/s^2), when the accelerometer drives the
  // velocity; otherwise the paper's form with its v_bx process noise.
  bool accelerometer_driven = false;
  double accel_input_mps2 = 0.0;
  double pitch_sd_rad = 0.0;   // the attitude source's stated pitch sd, seen through gravity
  double imu_period_s = 0.01;  // the accelerometer's sample interval, for its input noise
};

class WardPropagator {
 public:
  WardPropagator(const ProcessNoiseConfig& process, double imu_sd_accel_mps2);

  // x and P from their time to dt later.
  void Predict(double dt, const PropagationInput& input, const ward::AttitudeLoads<double>& loads,
               const ward::Params& params, ekf::StateVector* x, ekf::StateMatrix* P);
  // The accelerometer's normalized innovation squared at an update: an EMA of it drives w3.
  void ObserveAccelerometerNis(double nis);
  // The disturbance's random-walk density w3 the next prediction takes (m/s^3/sqrt(Hz)): the
  // model's, scaled by the recent accelerometer NIS and capped (the adaptive w3).
  double DisturbanceDensity() const;

 private:
  ProcessNoiseConfig q_;
  double imu_sd_accel_mps2_;
  double accel_nis_ema_ = 1.0;
  // The biases' discrete variances for the last step length and attitude sd (recomputed when
  // either changes).
  double bias_noise_dt_ = -1.0, bias_noise_pitch_sd_rad_ = 0.0;
  double accel_bias_q_ = 0.0, gyro_bias_q_ = 0.0;
};

}  // namespace slipgraph
