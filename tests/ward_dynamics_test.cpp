#include "factors/ward_dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/jacobian_check.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices read better unqualified in tests

const Params kParams = testing::LagrParams();

TEST(WardDynamics, FreeRollingOnFlatGroundDeceleratesByRollingResistance) {
  // Wheels turning exactly at ground speed (v_rel = 0): no traction, all four wheels roll.
  // v' = -g (R1 (1 - exp(-A_roll v)) + R2 v) + a_dist, with v = 1: -0.39226... + (-0.5).
  double x[kStateSize] = {1.0, 0.0, -0.5, 4.0, 4.0, 0.0, 0.0};
  double x_dot[kStateSize];
  StateDerivative(x, Attitude<double>{0.0, 0.0}, kParams, x_dot);
  const double expected = -9.80665 * (0.03 * (1.0 - std::exp(-20.0)) + 0.01) - 0.5;
  EXPECT_NEAR(x_dot[kVbx], expected, 1e-12);
  EXPECT_NEAR(x_dot[kYawRate], 0.0, 1e-12);  // symmetric
  EXPECT_EQ(x_dot[kAdist], 0.0);
}

TEST(WardDynamics, UphillSlopeAddsGravityComponent) {
  // REP-103 pitch -0.1 rad is nose up: Ward's phi = +0.1, gravity decelerates by g sin(0.1).
  double x[kStateSize] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double x_dot[kStateSize];
  StateDerivative(x, Attitude<double>{0.0, -0.1}, kParams, x_dot);
  EXPECT_NEAR(x_dot[kVbx], -9.80665 * std::sin(0.1), 1e-12);
}

TEST(WardDynamics, BiasesDecayWithTheirCorrelationTime) {
  double x[kStateSize] = {0.0, 0.3, 0.0, 0.0, 0.0, 0.0, -0.02};
  double x_dot[kStateSize];
  StateDerivative(x, Attitude<double>{0.0, 0.0}, kParams, x_dot);
  EXPECT_DOUBLE_EQ(x_dot[kAccelBias], -0.3 / kParams.accel_bias_tau_s);
  EXPECT_DOUBLE_EQ(x_dot[kGyroBias], 0.02 / kParams.gyro_bias_tau_s);
}

TEST(WardDynamics, GaussMarkovStepVarianceIsTheExactDiscretization) {
  // Over one time constant: sd^2 (1 - e^-2); over a short step about 2 sd^2 dt / tau; over a
  // long one the stationary variance.
  EXPECT_NEAR(GaussMarkovStepVariance(0.1, 300.0, 300.0), 0.01 * (1.0 - std::exp(-2.0)), 1e-15);
  EXPECT_NEAR(GaussMarkovStepVariance(0.1, 300.0, 0.01), 0.01 * 2.0 * 0.01 / 300.0, 1e-10);
  EXPECT_NEAR(GaussMarkovStepVariance(0.1, 300.0, 1e5), 0.01, 1e-15);
  // Its stationarity: a decay over dt plus the step's variance keeps sd^2.
  const double decay = std::exp(-2.5 / 300.0);
  EXPECT_NEAR(decay * decay * 0.01 + GaussMarkovStepVariance(0.1, 300.0, 2.5), 0.01, 1e-15);
}

TEST(WardDynamics, FasterRightWheelTurnsLeft) {
  // REP-103: counter-clockwise yaw is positive, so more right traction gives yaw' > 0.
  double x[kStateSize] = {0.5, 0.0, 0.0, 2.0, 2.4, 0.0, 0.0};
  const TireForces<double> f = ComputeTireForces(x, Attitude<double>{0.0, 0.0}, kParams);
  EXPECT_GT(f.traction_right_n, f.traction_left_n);
  EXPECT_GT(f.g_tire_radps2, 0.0);
  EXPECT_NEAR(f.v_rel_right_mps, 0.25 * 2.4 - 0.5, 1e-15);
}

TEST(WardDynamics, HoldBackForceBalance) {
  // Robot held still (v = 0) with both wheels spinning fast: traction saturates near
  // C1 N_front + C2 N_front v_rel; a_dist that balances it leaves v' = 0.
  double x[kStateSize] = {0.0, 0.0, 0.0, 4.0, 4.0, 0.0, 0.0};
  const TireForces<double> f = ComputeTireForces(x, Attitude<double>{0.0, 0.0}, kParams);
  const double front = 117.0 * 9.80665 * 0.55 / 0.9;  // both front wheels
  EXPECT_NEAR(f.f_tire_mps2 * 117.0, front * (0.8 * (1.0 - std::exp(-20.0)) + 0.05 * 1.0), 1e-9);
  x[kAdist] = -f.f_tire_mps2;
  double x_dot[kStateSize];
  StateDerivative(x, Attitude<double>{0.0, 0.0}, kParams, x_dot);
  EXPECT_NEAR(x_dot[kVbx], 0.0, 1e-12);
}

// Weak constraint 3's force: the tires on the body held still, whatever the velocity read.
TEST(WardDynamics, HeldStillTireForceReadsTheBodyAtRest) {
  const double held[kStateSize] = {0.0, 0.0, 0.0, 4.0, 4.0, 0.0, 0.0};
  const double backwards[kStateSize] = {-0.04, 0.1, -2.0, 4.0, 4.0, 0.0, 0.0};
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(Attitude<double>{0.0, 0.05}, kParams);
  const double at_rest = ComputeTireForces(held, loads, kParams).f_tire_mps2;
  EXPECT_DOUBLE_EQ(HeldStillTireForce(backwards, loads, kParams), at_rest);
  EXPECT_NE(ComputeTireForces(backwards, loads, kParams).f_tire_mps2, at_rest);
}

struct DerivativeFn {
  Params params;
  template <typename T>
  void operator()(const T* x, T* y) const {
    StateDerivative(x, Attitude<T>{T(0.05), T(-0.08)}, params, y);
  }
};

void ExpectJacobianMatches(const Params& params, const double* x) {
  const DerivativeFn f{params};
  const auto ad = testing::AutoDiffJacobian<kStateSize, kStateSize>(f, x);
  const auto nd = testing::CentralDifferenceJacobian<kStateSize, kStateSize>(f, x);
  EXPECT_LT(testing::MaxRelativeDifference(ad, nd), 1e-5) << "autodiff\n"
                                                          << ad << "\nnumeric\n"
                                                          << nd;
}

TEST(WardDynamics, JacobianMatchesCentralDifferencesAtZeroVelocityPoints) {
  // At rest (v_fwd = 0 and v_rel = 0 on both sides) and with v_rel = 0 while moving.
  const double at_rest[kStateSize] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const double rolling_freely[kStateSize] = {1.0, 0.01, -0.2, 4.0, 4.0, 0.0, 0.001};
  for (VehicleType type : {VehicleType::kDiffDriveCastor, VehicleType::kSkidSteer}) {
    ExpectJacobianMatches(testing::LagrParams(type), at_rest);
    ExpectJacobianMatches(testing::LagrParams(type), rolling_freely);
  }
  // The derivative in v at rest must carry the smooth slopes (a naive sign() law gives 0 here):
  // d v' / d v = -(N_front (C1 At + C2) + N_all (R1 A_roll + R2)) / m, N from eqs. (3)-(5).
  const auto ad = testing::AutoDiffJacobian<kStateSize, kStateSize>(DerivativeFn{kParams}, at_rest);
  const auto n = DiffDriveCastorNormalForcesN(117.0 * 9.80665, 0.05, 0.08, 0.35, 0.55, 0.55, 0.3);
  const double front = n.front_left_n + n.front_right_n;
  const double all = front + 2.0 * n.rear_each_n;
  EXPECT_NEAR(ad(kVbx, kVbx), -(front * (0.8 * 20.0 + 0.05) + all * (0.03 * 20.0 + 0.01)) / 117.0,
              1e-9);
}

TEST(WardDynamics, JacobianMatchesCentralDifferencesAtSeededRandomPoints) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const double x[kStateSize] = {1.5 * u(rng), 0.1 * u(rng), 3.0 * u(rng), 6.0 * u(rng),
                                  6.0 * u(rng), 1.0 * u(rng), 0.01 * u(rng)};
    ExpectJacobianMatches(kParams, x);
  }
}

TEST(WardDynamics, PropagateConvergesToTheEquilibriumSpeedAndIsStableAt50Hz) {
  // Driving on flat ground with wheels at 4 rad/s (1 m/s surface speed): velocity settles where
  // traction balances rolling resistance, slightly below 1 m/s. dt = 0.02 s is where forward
  // Euler diverges for these tire values.
  double x[kStateSize] = {0.0, 0.0, 0.0, 4.0, 4.0, 0.0, 0.0};
  for (int k = 0; k < 200; ++k) {
    double next[kStateSize];
    Propagate(x, Attitude<double>{0.0, 0.0}, kParams, 0.02, next);
    std::copy(next, next + kStateSize, x);
  }
  double x_dot[kStateSize];
  StateDerivative(x, Attitude<double>{0.0, 0.0}, kParams, x_dot);
  EXPECT_NEAR(x_dot[kVbx], 0.0, 1e-9);
  EXPECT_GT(x[kVbx], 0.95);
  EXPECT_LT(x[kVbx], 1.0);
}

TEST(WardDynamics, PropagateInstantiatesWithJets) {
  using Jet = ceres::Jet<double, kStateSize>;
  Jet x[kStateSize], next[kStateSize];
  const double values[kStateSize] = {0.5, 0.0, -0.1, 2.0, 2.1, 0.05, 0.0};
  for (int i = 0; i < kStateSize; ++i) x[i] = Jet(values[i], i);
  Propagate(x, Attitude<Jet>{Jet(0.0), Jet(0.0)}, kParams, 0.01, next);
  EXPECT_TRUE(std::isfinite(next[kVbx].a));
  EXPECT_NEAR(next[kAdist].v[kAdist], 1.0, 1e-15);  // a_dist is a random walk: identity
}

}  // namespace
}  // namespace slipgraph
