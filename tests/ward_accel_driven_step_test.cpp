#include "factors/ward_accel_driven_step.h"

#include <gtest/gtest.h>

#include <random>

#include "factors/ward_dynamics.h"
#include "tests/jacobian_check.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices read better unqualified in tests
using StateMatrix = Eigen::Matrix<double, kStateSize, kStateSize>;

// The reference: the accelerometer-driven derivative through PropagateWith, differentiated by
// 7-wide Jets (what the EKF did before the chain rule).
struct ReferenceStep {
  double specific_force_mps2;
  const AttitudeLoads<double>& loads;
  const Params& params;
  double dt_s;
  template <typename T>
  void operator()(const T* x, T* x_next) const {
    PropagateWith(
        x,
        [&](const T* state, T* x_dot) {
          StateDerivative(state, loads, params, x_dot);
          x_dot[kVbx] = specific_force_mps2 - state[kAccelBias] - loads.gravity_along_x_mps2;
        },
        dt_s, x_next);
  }
};

// The same step as a function of the specific force alone, for its column.
struct ReferenceStepInForce {
  const double* x;
  const AttitudeLoads<double>& loads;
  const Params& params;
  double dt_s;
  template <typename T>
  void operator()(const T* specific_force_mps2, T* x_next) const {
    T start[kStateSize];
    for (int i = 0; i < kStateSize; ++i) start[i] = T(x[i]);
    PropagateWith(
        start,
        [&](const T* state, T* x_dot) {
          StateDerivative(state, loads, params, x_dot);
          x_dot[kVbx] = specific_force_mps2[0] - state[kAccelBias] - loads.gravity_along_x_mps2;
        },
        dt_s, x_next);
  }
};

void ExpectSameAsTheJetPass(const double* x, double specific_force_mps2,
                            const Attitude<double>& attitude, const Params& params, double dt_s) {
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(attitude, params);
  const ReferenceStep reference{specific_force_mps2, loads, params, dt_s};
  double expected[kStateSize];
  reference(x, expected);
  const StateMatrix expected_A = testing::AutoDiffJacobian<kStateSize, kStateSize>(reference, x);

  const Eigen::Matrix<double, kStateSize, 1> expected_column =
      testing::AutoDiffJacobian<1, kStateSize>(ReferenceStepInForce{x, loads, params, dt_s},
                                               &specific_force_mps2);

  double next[kStateSize];
  StateMatrix A;
  Eigen::Matrix<double, kStateSize, 1> column;
  PropagateAccelerometerDriven(x, specific_force_mps2, loads, params, dt_s, next, &A, &column);
  for (int i = 0; i < kStateSize; ++i) {
    // The same arithmetic on the values: equal to the last bit.
    EXPECT_EQ(next[i], expected[i]) << "state " << i;
  }
  // The chain rule sums the same products in another order: equal to rounding.
  for (int r = 0; r < kStateSize; ++r) {
    for (int c = 0; c < kStateSize; ++c) {
      EXPECT_NEAR(A(r, c), expected_A(r, c), 1e-12 * (1.0 + std::abs(expected_A(r, c))))
          << "A(" << r << ", " << c << ")";
    }
    EXPECT_NEAR(column(r), expected_column(r), 1e-12 * (1.0 + std::abs(expected_column(r))))
        << "d x_next / d specific force, row " << r;
  }
}

TEST(WardAccelDrivenStep, EqualsTheJetPassAtRandomStates) {
  const Params params = testing::LagrParams();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> speed(-1.5, 1.5), omega(-6.0, 6.0), yaw(-0.8, 0.8),
      small(-0.05, 0.05), angle(-0.2, 0.2);
  for (int trial = 0; trial < 50; ++trial) {
    const double x[kStateSize] = {speed(rng), small(rng), 10 * small(rng), omega(rng),
                                  omega(rng), yaw(rng),   small(rng)};
    const Attitude<double> attitude{angle(rng), angle(rng)};
    // 10 ms (one sub-step), 25 ms (three) and a 0.3 s gap (thirty).
    for (const double dt : {0.01, 0.025, 0.3}) {
      ExpectSameAsTheJetPass(x, 2.0 * speed(rng), attitude, params, dt);
    }
  }
}

TEST(WardAccelDrivenStep, EqualsTheJetPassWhereTheLawsTurnRound) {
  // v_rel = 0 and v_fwd = 0 on both sides: the saturations' Taylor branches.
  const Params params = testing::LagrParams();
  const double still[kStateSize] = {0.0, 0.01, -0.3, 0.0, 0.0, 0.0, 0.001};
  ExpectSameAsTheJetPass(still, 0.05, Attitude<double>{0.0, 0.0}, params, 0.01);
  const double rolling_free[kStateSize] = {0.5, 0.0, 0.0, 2.0, 2.0, 0.0, 0.0};
  ExpectSameAsTheJetPass(rolling_free, 0.0, Attitude<double>{0.0, 0.05}, params, 0.01);
}

TEST(WardAccelDrivenStep, AllWheelDriveVehicle) {
  const Params params = testing::LagrParams(VehicleType::kSkidSteer);
  const double x[kStateSize] = {0.4, 0.02, -0.5, 1.0, 2.5, 0.3, -0.004};
  ExpectSameAsTheJetPass(x, 0.3, Attitude<double>{0.05, -0.1}, params, 0.02);
}

}  // namespace
}  // namespace slipgraph
