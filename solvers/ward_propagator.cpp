#include "solvers/ward_propagator.h"

#include <ceres/jet.h>

#include <algorithm>
#include <cmath>

#include "factors/ward_accel_driven_step.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices

// A P A' for a transition matrix with few non-zeros per row: a_dist and the wheel speeds are
// random walks (identity rows; a_dist's scaled when it decays) and the biases decay on their
// own, so in the accelerometer-driven form 12 of the 49 entries are non-zero. Symmetric by
// construction (the lower half is mirrored).
template <int N>
Eigen::Matrix<double, N, N> Sandwich(const Eigen::Matrix<double, N, N>& A,
                                     const Eigen::Matrix<double, N, N>& P) {
  int count[N];
  int column[N][N];
  for (int r = 0; r < N; ++r) {
    count[r] = 0;
    for (int c = 0; c < N; ++c) {
      if (A(r, c) != 0.0) column[r][count[r]++] = c;
    }
  }
  Eigen::Matrix<double, N, N> AP;
  for (int r = 0; r < N; ++r) {
    AP.row(r).setZero();
    for (int k = 0; k < count[r]; ++k) AP.row(r) += A(r, column[r][k]) * P.row(column[r][k]);
  }
  Eigen::Matrix<double, N, N> out;
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c <= r; ++c) {
      double sum = 0.0;
      for (int k = 0; k < count[c]; ++k) sum += AP(r, column[c][k]) * A(c, column[c][k]);
      out(r, c) = out(c, r) = sum;
    }
  }
  return out;
}

}  // namespace

WardPropagator::WardPropagator(const ProcessNoiseConfig& process, double imu_sd_accel_mps2)
    : q_(process), imu_sd_accel_mps2_(imu_sd_accel_mps2) {}

void WardPropagator::ObserveAccelerometerNis(double nis) {
  const double weight = 2.0 / (1.0 + q_.a_dist_adapt_samples);
  accel_nis_ema_ += (nis - accel_nis_ema_) * weight;
}

double WardPropagator::DisturbanceDensity() const {
  return std::min(q_.a_dist_max_mps3_per_sqrt_hz,
                  q_.a_dist_mps3_per_sqrt_hz * std::sqrt(std::max(1.0, accel_nis_ema_)));
}

void WardPropagator::Predict(double dt, const PropagationInput& input,
                             const AttitudeLoads<double>& loads, const Params& params,
                             ekf::StateVector* x, ekf::StateMatrix* P) {
  ekf::StateMatrix A;
  if (input.accelerometer_driven) {
    // The state and its transition matrix by the chain rule through the RK4 stages: the same
    // state as a 7-wide Jet pass, cheaper.
    ekf::StateVector next;
    PropagateAccelerometerDriven(x->data(), input.accel_input_mps2, loads, params, dt, next.data(),
                                 &A);
    *x = next;
  } else {
    using Jet = ceres::Jet<double, kStateSize>;
    Jet x_jet[kStateSize], next[kStateSize];
    for (int i = 0; i < kStateSize; ++i) x_jet[i] = Jet((*x)(i), i);
    Propagate(x_jet, loads, params, dt, next);
    for (int r = 0; r < kStateSize; ++r) {
      (*x)(r) = next[r].a;
      A.row(r) = next[r].v.transpose();
    }
  }
  // A decaying disturbance (ProcessNoiseConfig::a_dist_decay_tau_s): its row of the transition
  // scaled by exp(-dt / tau), its noise the Gauss-Markov step's.
  const double a_dist_decay =
      q_.a_dist_decay_tau_s > 0.0 ? std::exp(-dt / q_.a_dist_decay_tau_s) : 1.0;
  if (a_dist_decay != 1.0) {
    (*x)(kAdist) *= a_dist_decay;
    A.row(kAdist) *= a_dist_decay;
  }
  ekf::StateVector q_diag;
  // Accelerometer-driven: the input's white noise (accelerometer and pitch through gravity).
  const double accel_density_sq = AccelInputDensitySq(imu_sd_accel_mps2_, input.pitch_sd_rad,
                                                      params.gravity_mps2, input.imu_period_s);
  q_diag(kVbx) =
      (input.accelerometer_driven ? accel_density_sq
                                  : q_.v_bx_mps2_per_sqrt_hz * q_.v_bx_mps2_per_sqrt_hz) *
      dt;
  // b_ax walks by its own Gauss-Markov process and by the attitude's slow error, which reaches
  // the velocity only through the gravity the accelerometer input removes
  // (ProcessNoiseConfig::attitude_error_walk_s).
  const double bias_pitch_sd_rad = input.accelerometer_driven ? input.pitch_sd_rad : 0.0;
  if (dt != bias_noise_dt_ || bias_pitch_sd_rad != bias_noise_pitch_sd_rad_) {
    bias_noise_dt_ = dt;
    bias_noise_pitch_sd_rad_ = bias_pitch_sd_rad;
    const double attitude_mps2 = params.gravity_mps2 * bias_pitch_sd_rad;
    accel_bias_q_ = GaussMarkovStepVariance(q_.accel_bias_sd_mps2, q_.accel_bias_tau_s, dt);
    if (q_.attitude_error_walk_s > 0.0) {
      accel_bias_q_ += attitude_mps2 * attitude_mps2 * dt / q_.attitude_error_walk_s;
    }
    gyro_bias_q_ = GaussMarkovStepVariance(q_.gyro_bias_sd_radps, q_.gyro_bias_tau_s, dt);
  }
  q_diag(kAccelBias) = accel_bias_q_;
  // Adaptive w3: the density scales with the recent accelerometer NIS (1 when consistent).
  const double q_adist = DisturbanceDensity();
  q_diag(kAdist) =
      a_dist_decay != 1.0
          ? GaussMarkovStepVariance(GaussMarkovStationarySd(q_adist, q_.a_dist_decay_tau_s),
                                    q_.a_dist_decay_tau_s, dt)
          : q_adist * q_adist * dt;
  q_diag(kOmegaLeft) = q_diag(kOmegaRight) =
      q_.omega_radps2_per_sqrt_hz * q_.omega_radps2_per_sqrt_hz * dt;
  q_diag(kYawRate) = q_.yaw_rate_radps2_per_sqrt_hz * q_.yaw_rate_radps2_per_sqrt_hz * dt;
  q_diag(kGyroBias) = gyro_bias_q_;
  *P = Sandwich(A, *P);
  P->diagonal() += q_diag;
}

}  // namespace slipgraph
