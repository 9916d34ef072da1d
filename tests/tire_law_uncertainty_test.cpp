// The tire law's variance at a state: each term against its definition, with the traction's
// slope in the wheel speeds taken by central differences of the shared physics, and the
// per-sample scale for a correlated error.
#include "factors/tire_law_uncertainty.h"

#include <gtest/gtest.h>

#include <cmath>

#include "factors/ward_state.h"
#include "tests/ward_test_params.h"

namespace slipgraph {
namespace {

using namespace ward;

struct Case {
  double x[kStateSize];
  AttitudeLoads<double> loads;
  Params params;
};

Case Driving() {
  Case c{{0.8, 0.0, 0.0, 3.6, 3.9, 0.0, 0.0}, {}, testing::LagrParams()};
  c.loads = ComputeAttitudeLoads(Attitude<double>{0.02, -0.05}, c.params);
  return c;
}

// (Traction of both sides) / mass, and its slope in one wheel speed by central differences.
double Traction(const Case& c, const double* x) {
  const TireForces<double> f = ComputeTireForces(x, c.loads, c.params);
  return (f.traction_left_n + f.traction_right_n) / c.params.mass_kg;
}

double Slope(const Case& c, int wheel) {
  double plus[kStateSize], minus[kStateSize];
  std::copy(c.x, c.x + kStateSize, plus);
  std::copy(c.x, c.x + kStateSize, minus);
  const double h = 1e-6;
  plus[wheel] += h;
  minus[wheel] -= h;
  return (Traction(c, plus) - Traction(c, minus)) / (2.0 * h);
}

TEST(TireLawUncertainty, RelativeAndFloorTerms) {
  const Case c = Driving();
  TireLawUncertainty u;
  u.relative_sd = 0.3;
  u.floor_mps2 = 0.1;
  const double traction = std::abs(Traction(c, c.x));
  ASSERT_GT(traction, 0.1);
  EXPECT_NEAR(TireLawVariance(c.x, c.loads, c.params, u),
              0.3 * 0.3 * traction * traction + 0.1 * 0.1, 1e-12);
}

TEST(TireLawUncertainty, SlipTermsUseTheTractionsSlopeInEachWheel) {
  const Case c = Driving();
  TireLawUncertainty u;
  u.relative_sd = 0.0;
  u.floor_mps2 = 0.0;
  u.slip_relative_sd = 0.2;
  u.slip_floor_mps = 0.01;
  const TireForces<double> f = ComputeTireForces(c.x, c.loads, c.params);
  // d traction / d v_rel = (d traction / d w) / r.
  const double r = c.params.wheel_radius_m;
  const double left =
      std::abs(Slope(c, kOmegaLeft)) / r * (0.2 * std::abs(f.v_rel_left_mps) + 0.01);
  const double right =
      std::abs(Slope(c, kOmegaRight)) / r * (0.2 * std::abs(f.v_rel_right_mps) + 0.01);
  ASSERT_GT(left, 0.0);
  ASSERT_GT(right, 0.0);
  EXPECT_NEAR(TireLawVariance(c.x, c.loads, c.params, u), left * left + right * right,
              1e-6 * (left * left + right * right));
}

TEST(TireLawUncertainty, CorrelatedErrorScalesThePerSampleVariance) {
  const Case c = Driving();
  TireLawUncertainty u;
  const double plain = TireLawVariance(c.x, c.loads, c.params, u);
  EXPECT_DOUBLE_EQ(TireLawSampleVariance(c.x, c.loads, c.params, u, 0.01), plain);
  u.correlation_time_s = 0.5;
  EXPECT_DOUBLE_EQ(TireLawSampleScale(u, 0.01), 50.0);
  EXPECT_NEAR(TireLawSampleVariance(c.x, c.loads, c.params, u, 0.01), 50.0 * plain, 1e-12);
  EXPECT_DOUBLE_EQ(TireLawSampleScale(u, 1.0), 1.0);  // never below the plain variance
}

}  // namespace
}  // namespace slipgraph
