// The EKF's prediction: the state as the shared RK4 step gives it, the covariance A P A' + Q with
// A the step's Jacobian (checked by central differences), Q's entries as their densities and the
// Gauss-Markov biases say, and w3 growing with the accelerometer's normalized innovations.
#include "solvers/ward_propagator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "factors/ward_accel_driven_step.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices

const Params kParams = testing::LagrParams();

ekf::StateVector Moving() { return testing::MovingWardState(); }

// The prediction's transition matrix by central differences of the state it predicts.
ekf::StateMatrix NumericTransition(const PropagationInput& input, const AttitudeLoads<double>& l,
                                   double dt, const ProcessNoiseConfig& q = {}) {
  ekf::StateMatrix A;
  for (int c = 0; c < kStateSize; ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(Moving()(c)));
    ekf::StateVector plus = Moving(), minus = Moving();
    plus(c) += h;
    minus(c) -= h;
    ekf::StateMatrix P = ekf::StateMatrix::Zero();
    WardPropagator(q, 0.05).Predict(dt, input, l, kParams, &plus, &P);
    WardPropagator(q, 0.05).Predict(dt, input, l, kParams, &minus, &P);
    A.col(c) = (plus - minus) / (2.0 * h);
  }
  return A;
}

TEST(WardPropagator, CovarianceIsTheStepJacobianSandwichPlusQ) {
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(Attitude<double>{0.02, -0.05}, kParams);
  const double dt = 0.01;
  for (const bool driven : {true, false}) {
    PropagationInput input;
    input.accelerometer_driven = driven;
    input.accel_input_mps2 = 0.3;
    input.pitch_sd_rad = 0.01;
    const ProcessNoiseConfig q;
    ekf::StateVector x = Moving();
    ekf::StateMatrix P0 = 0.01 * ekf::StateMatrix::Identity();
    P0(0, 2) = P0(2, 0) = 0.004;
    ekf::StateMatrix P_zero = ekf::StateMatrix::Zero();
    ekf::StateVector x_zero = Moving();
    WardPropagator(q, 0.05).Predict(dt, input, loads, kParams, &x_zero, &P_zero);
    ekf::StateMatrix P = P0;
    WardPropagator(q, 0.05).Predict(dt, input, loads, kParams, &x, &P);
    EXPECT_EQ(x, x_zero);  // the state does not depend on P
    const ekf::StateMatrix A = NumericTransition(input, loads, dt);
    const ekf::StateMatrix expected = A * P0 * A.transpose() + P_zero;
    EXPECT_LT((P - expected).cwiseAbs().maxCoeff(), 1e-8) << (driven ? "driven" : "paper's");
    // Q alone: diagonal, each entry as its source says; the attitude's error walks the bias
    // where the accelerometer drives (g sd_pitch in attitude_error_walk_s).
    const double attitude_mps2 = kParams.gravity_mps2 * input.pitch_sd_rad;
    EXPECT_DOUBLE_EQ(
        P_zero(kAccelBias, kAccelBias),
        GaussMarkovStepVariance(q.accel_bias_sd_mps2, q.accel_bias_tau_s, dt) +
            (driven ? attitude_mps2 * attitude_mps2 * dt / q.attitude_error_walk_s : 0.0));
    EXPECT_DOUBLE_EQ(P_zero(kGyroBias, kGyroBias),
                     GaussMarkovStepVariance(q.gyro_bias_sd_radps, q.gyro_bias_tau_s, dt));
    EXPECT_DOUBLE_EQ(P_zero(kAdist, kAdist),
                     q.a_dist_mps3_per_sqrt_hz * q.a_dist_mps3_per_sqrt_hz * dt);
    const double v_density_sq =
        driven ? AccelInputDensitySq(0.05, input.pitch_sd_rad, kParams.gravity_mps2, 0.01)
               : q.v_bx_mps2_per_sqrt_hz * q.v_bx_mps2_per_sqrt_hz;
    EXPECT_DOUBLE_EQ(P_zero(kVbx, kVbx), v_density_sq * dt);
    EXPECT_EQ(P_zero(kVbx, kAdist), 0.0);
  }
}

// The bias's step variance follows the attitude's stated sd from one step to the next.
TEST(WardPropagator, TheBiasWalkFollowsTheAttitudesStatedSd) {
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(Attitude<double>{0.0, 0.0}, kParams);
  const ProcessNoiseConfig q;
  WardPropagator propagator(q, 0.05);
  PropagationInput input;
  input.accelerometer_driven = true;
  double bias_q[2];
  for (int i = 0; i < 2; ++i) {
    input.pitch_sd_rad = i == 0 ? 0.002 : 0.02;
    ekf::StateVector x = Moving();
    ekf::StateMatrix P = ekf::StateMatrix::Zero();
    propagator.Predict(0.01, input, loads, kParams, &x, &P);
    bias_q[i] = P(kAccelBias, kAccelBias);
  }
  const double own = GaussMarkovStepVariance(q.accel_bias_sd_mps2, q.accel_bias_tau_s, 0.01);
  EXPECT_NEAR((bias_q[1] - own) / (bias_q[0] - own), 100.0, 1e-6);
}

TEST(WardPropagator, DisturbanceNoiseGrowsWithTheAccelerometerNis) {
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(Attitude<double>{0.0, 0.0}, kParams);
  const ProcessNoiseConfig q;
  WardPropagator propagator(q, 0.05);
  const auto q_adist = [&] {
    ekf::StateVector x = Moving();
    ekf::StateMatrix P = ekf::StateMatrix::Zero();
    propagator.Predict(0.01, {}, loads, kParams, &x, &P);
    return P(kAdist, kAdist);
  };
  const double consistent = q_adist();
  for (int i = 0; i < 50; ++i) propagator.ObserveAccelerometerNis(4.0);
  const double inflated = q_adist();
  // The density a smoother behind the filter takes (FilterResult::disturbance_density).
  EXPECT_NEAR(std::pow(propagator.DisturbanceDensity(), 2) * 0.01, inflated, 1e-12);
  EXPECT_NEAR(inflated / consistent,
              std::min(4.0, std::pow(q.a_dist_max_mps3_per_sqrt_hz / q.a_dist_mps3_per_sqrt_hz, 2)),
              1e-6);
  // A NIS below 1 never lowers the density below its base.
  for (int i = 0; i < 50; ++i) propagator.ObserveAccelerometerNis(0.01);
  EXPECT_DOUBLE_EQ(q_adist(), consistent);
}

TEST(WardPropagator, ADecayingDisturbanceIsAGaussMarkovProcess) {
  // a_dist' = -a_dist / tau + w: over dt its mean decays by exp(-dt / tau) and its variance
  // tends to the stationary w^2 tau / 2.
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(Attitude<double>{0.0, 0.0}, kParams);
  ProcessNoiseConfig q;
  q.a_dist_mps3_per_sqrt_hz = q.a_dist_max_mps3_per_sqrt_hz = 0.6;
  q.a_dist_decay_tau_s = 0.5;
  const double dt = 0.01, decay = std::exp(-dt / 0.5), stationary_sd = 0.6 * std::sqrt(0.25);
  WardPropagator propagator(q, 0.05);
  ekf::StateVector x = Moving();
  x(kAdist) = -2.0;
  ekf::StateMatrix P = 0.01 * ekf::StateMatrix::Identity();
  propagator.Predict(dt, {}, loads, kParams, &x, &P);
  EXPECT_NEAR(x(kAdist), -2.0 * decay, 1e-12);
  EXPECT_NEAR(P(kAdist, kAdist),
              0.01 * decay * decay + GaussMarkovStepVariance(stationary_sd, 0.5, dt), 1e-12);
  for (int i = 0; i < 2000; ++i) propagator.Predict(dt, {}, loads, kParams, &x, &P);
  EXPECT_NEAR(x(kAdist), 0.0, 1e-6);
  EXPECT_NEAR(std::sqrt(P(kAdist, kAdist)), stationary_sd, 1e-3);
  // The transition's a_dist row is scaled too: with a correlation between v_bx and a_dist the
  // covariance is the numeric transition's sandwich plus Q, in either velocity model.
  for (const bool driven : {true, false}) {
    PropagationInput input;
    input.accelerometer_driven = driven;
    input.accel_input_mps2 = 0.3;
    ekf::StateMatrix P0 = 0.01 * ekf::StateMatrix::Identity();
    P0(kVbx, kAdist) = P0(kAdist, kVbx) = 0.004;
    ekf::StateMatrix P_zero = ekf::StateMatrix::Zero(), P_step = P0;
    ekf::StateVector x_zero = Moving(), x_step = Moving();
    WardPropagator(q, 0.05).Predict(dt, input, loads, kParams, &x_zero, &P_zero);
    WardPropagator(q, 0.05).Predict(dt, input, loads, kParams, &x_step, &P_step);
    const ekf::StateMatrix A = NumericTransition(input, loads, dt, q);
    EXPECT_NEAR(A(kAdist, kAdist), decay, 1e-6);
    EXPECT_LT((P_step - (A * P0 * A.transpose() + P_zero)).cwiseAbs().maxCoeff(), 1e-8);
  }
  // Without a correlation time it is the paper's random walk: the mean stays.
  q.a_dist_decay_tau_s = 0.0;
  ekf::StateVector walk = Moving();
  walk(kAdist) = -2.0;
  ekf::StateMatrix P_walk = ekf::StateMatrix::Zero();
  WardPropagator(q, 0.05).Predict(dt, {}, loads, kParams, &walk, &P_walk);
  EXPECT_DOUBLE_EQ(walk(kAdist), -2.0);
  EXPECT_DOUBLE_EQ(P_walk(kAdist, kAdist), 0.36 * dt);
}

}  // namespace
}  // namespace slipgraph
