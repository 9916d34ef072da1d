#include "factors/tire_acceleration_partials.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT: state indices read better unqualified in tests

// Against central differences of the plain double evaluation: catches a slot mix-up that a
// comparison with another Jet pass would share.
void ExpectTheTireForcesDerivatives(const double* x, const Attitude<double>& attitude,
                                    const Params& params) {
  const AttitudeLoads<double> loads = ComputeAttitudeLoads(attitude, params);
  const TireAccelerations a = TireAccelerationsWithPartials(x, loads, params);
  const auto body_x = [&](const double* state) {
    return ComputeTireForces(state, loads, params).f_tire_mps2;
  };
  const auto yaw = [&](const double* state) {
    return ComputeTireForces(state, loads, params).g_tire_radps2;
  };
  // The Jets' values are the same arithmetic up to the last bits of the laws' functions.
  EXPECT_NEAR(a.body_x.value, body_x(x), 1e-14 * (1.0 + std::abs(body_x(x))));
  EXPECT_NEAR(a.yaw.value, yaw(x), 1e-14 * (1.0 + std::abs(yaw(x))));
  const int slots[4] = {kVbx, kYawRate, kOmegaLeft, kOmegaRight};
  const TireAccelerationPartials* each[2] = {&a.body_x, &a.yaw};
  for (int which = 0; which < 2; ++which) {
    const TireAccelerationPartials& g = *each[which];
    const double partials[4] = {g.d_v_bx, g.d_yaw_rate, g.d_omega_left, g.d_omega_right};
    for (int k = 0; k < 4; ++k) {
      double plus[kStateSize], minus[kStateSize];
      std::copy(x, x + kStateSize, plus);
      std::copy(x, x + kStateSize, minus);
      const double h = 1e-6;
      plus[slots[k]] += h;
      minus[slots[k]] -= h;
      const double numeric = which == 0 ? (body_x(plus) - body_x(minus)) / (2.0 * h)
                                        : (yaw(plus) - yaw(minus)) / (2.0 * h);
      EXPECT_NEAR(partials[k], numeric, 1e-6 * (1.0 + std::abs(numeric)))
          << (which == 0 ? "f_tire" : "g_tire") << ", slot " << k;
      EXPECT_NE(partials[k], 0.0) << (which == 0 ? "f_tire" : "g_tire") << ", slot " << k;
    }
  }
}

TEST(TireAccelerationPartials, AreTheTireForcesDerivativesInATurn) {
  const double x[kStateSize] = {0.6, 0.0, 0.0, 2.2, 2.9, 0.15, 0.0};
  ExpectTheTireForcesDerivatives(x, Attitude<double>{0.03, -0.04}, testing::LagrParams());
}

TEST(TireAccelerationPartials, AreTheTireForcesDerivativesOfAnAllWheelDriveVehicle) {
  const double x[kStateSize] = {0.4, 0.02, -0.5, 1.0, 2.5, 0.3, -0.004};
  ExpectTheTireForcesDerivatives(x, Attitude<double>{0.05, -0.1},
                                 testing::LagrParams(VehicleType::kSkidSteer));
}

}  // namespace
}  // namespace slipgraph
