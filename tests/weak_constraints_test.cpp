#include "solvers/weak_constraints.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT

std::vector<PseudoMeasurement> Collect(const double* x, const WeakConstraintInputs& in,
                                       const double* x_prev = nullptr) {
  std::vector<PseudoMeasurement> out;
  CollectWeakConstraints(x, x_prev ? x_prev : x, in, WeakConstraintConfig(), &out);
  return out;
}

int Count(const std::vector<PseudoMeasurement>& out, WeakConstraint c) {
  int n = 0;
  for (const auto& p : out) n += p.constraint == c;
  return n;
}

const PseudoMeasurement* Find(const std::vector<PseudoMeasurement>& out, WeakConstraint c,
                              int index) {
  for (const auto& p : out) {
    if (p.constraint == c && p.state_index == index) return &p;
  }
  return nullptr;
}

TEST(WeakConstraints, NothingAppliesInOrdinaryDriving) {
  const double x[kStateSize] = {1.0, 0.0, -0.3, 4.0, 4.0, 0.0, 0.0};
  WeakConstraintInputs in;
  in.dt_s = 0.01, in.vel_dir = 1.0, in.slip_ema = 0.05, in.slip_ema_rate_per_s = -0.1;
  EXPECT_TRUE(Collect(x, in).empty());
}

TEST(WeakConstraints, Wc1DisturbanceMustOpposeMotion) {
  const double x[kStateSize] = {1.0, 0.0, 0.4, 4.0, 4.0, 0.0, 0.0};  // pushing forward
  WeakConstraintInputs in;
  in.vel_dir = 1.0;
  const auto out = Collect(x, in);
  const PseudoMeasurement* p = Find(out, WeakConstraint::kOpposeMotion, kAdist);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->z, 0.0);  // innovation 0 - x3
  in.vel_dir = 0.0;      // wheels stopped: no direction, no constraint
  EXPECT_EQ(Count(Collect(x, in), WeakConstraint::kOpposeMotion), 0);
}

// WC1's variance grows by 1 + (a_dist / scale)^2 (a Cauchy weight): a small push is held at the
// paper's sd, a push of several m/s^2 (the tire law failing in a transient) hardly at all.
TEST(WeakConstraints, Wc1IsDoubtedAsThePushGrows) {
  WeakConstraintInputs in;
  in.vel_dir = -1.0;  // reversing: a backward disturbance pushes
  WeakConstraintConfig config;
  ASSERT_EQ(config.oppose_motion_cauchy_scale_mps2, 1.0);
  const auto density = [&](double a_dist) {
    const double x[kStateSize] = {-1.0, 0.0, a_dist, -4.0, -4.0, 0.0, 0.0};
    std::vector<PseudoMeasurement> out;
    CollectWeakConstraints(x, x, in, config, &out);
    const PseudoMeasurement* p = Find(out, WeakConstraint::kOpposeMotion, kAdist);
    return p != nullptr ? p->density : -1.0;
  };
  EXPECT_DOUBLE_EQ(density(-0.4), 0.1 * std::sqrt(1.0 + 0.16));
  EXPECT_DOUBLE_EQ(density(-3.0), 0.1 * std::sqrt(10.0));
  EXPECT_EQ(density(0.5), -1.0);                 // opposing the motion: no constraint
  config.oppose_motion_cauchy_scale_mps2 = 0.0;  // the paper's
  EXPECT_DOUBLE_EQ(density(-3.0), 0.1);
}

TEST(WeakConstraints, Wc2DecaysASlowlyGrowingDisturbanceWhileSlipIsSmall) {
  const double x[kStateSize] = {1.0, 0.0, -0.8, 4.0, 4.0, 0.0, 0.0};
  WeakConstraintInputs in;
  const WeakConstraintConfig c;
  in.vel_dir = 1.0, in.slip_ema = 0.5 * c.slip_threshold;
  in.slip_ema_rate_per_s = 0.5 * c.min_slip_rate_per_s;
  const auto out = Collect(x, in);
  const PseudoMeasurement* p = Find(out, WeakConstraint::kActQuickly, kAdist);
  ASSERT_NE(p, nullptr);
  EXPECT_DOUBLE_EQ(p->z, WeakConstraintConfig().decay_alpha * -0.8);  // alpha x3
  in.slip_ema_rate_per_s = 5.0;                                       // fast: a real event
  EXPECT_EQ(Count(Collect(x, in), WeakConstraint::kActQuickly), 0);
  in.slip_ema_rate_per_s = 0.5 * c.min_slip_rate_per_s;
  in.slip_ema = 2.0 * c.slip_threshold;  // already slipping a lot
  EXPECT_EQ(Count(Collect(x, in), WeakConstraint::kActQuickly), 0);
}

TEST(WeakConstraints, Wc3DisturbanceMayNotPullTheRobotBackwards) {
  // Wheels forward, robot moving backwards.
  double x[kStateSize] = {-0.2, 0.0, -3.0, 4.0, 4.0, 0.0, 0.0};
  WeakConstraintInputs in;
  in.vel_dir = 1.0;
  // a) net tire force pulls backwards too (e.g. rolling back downhill): disturbance to zero.
  in.f_tire_mps2 = -0.5, in.gravity_along_x_mps2 = 0.0;
  const auto out_a = Collect(x, in);
  const PseudoMeasurement* a = Find(out_a, WeakConstraint::kNoPullBack, kAdist);
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->z, 0.0);
  // b) tires push forward 2.0 on a slope needing 0.5: the disturbance at most holds the robot,
  //    max(g sin(phi) - f_tire, x3) = max(0.5 - 2.0, -3.0) = -1.5.
  in.f_tire_mps2 = 2.0, in.gravity_along_x_mps2 = 0.5;
  const auto out = Collect(x, in);
  const PseudoMeasurement* b = Find(out, WeakConstraint::kNoPullBack, kAdist);
  ASSERT_NE(b, nullptr);
  EXPECT_DOUBLE_EQ(b->z, -1.5);
  // Mirror image in reverse.
  double r[kStateSize] = {0.2, 0.0, 3.0, -4.0, -4.0, 0.0, 0.0};
  in.vel_dir = -1.0, in.f_tire_mps2 = -2.0, in.gravity_along_x_mps2 = -0.5;
  const auto out_m = Collect(r, in);
  const PseudoMeasurement* m = Find(out_m, WeakConstraint::kNoPullBack, kAdist);
  ASSERT_NE(m, nullptr);
  EXPECT_DOUBLE_EQ(m->z, 1.5);
}

TEST(WeakConstraints, Wc4AtRestBiasesAndDisturbanceGoToZero) {
  const double x[kStateSize] = {0.0, 0.01, -0.2, 0.0, 0.0, 0.0, 0.001};
  WeakConstraintInputs in;
  in.wheels_stopped_s = WeakConstraintConfig().stop_time_s - 0.01;
  EXPECT_EQ(Count(Collect(x, in), WeakConstraint::kAtRest), 0);
  in.wheels_stopped_s = WeakConstraintConfig().stop_time_s;
  const auto out = Collect(x, in);
  EXPECT_EQ(Count(out, WeakConstraint::kAtRest), 3);
  EXPECT_NE(Find(out, WeakConstraint::kAtRest, kAccelBias), nullptr);
  EXPECT_NE(Find(out, WeakConstraint::kAtRest, kAdist), nullptr);
  EXPECT_NE(Find(out, WeakConstraint::kAtRest, kGyroBias), nullptr);
}

TEST(WeakConstraints, Wc5BoundsAndWc6RateLimits) {
  const WeakConstraintConfig c;
  double x[kStateSize] = {c.max_v_bx_mps + 1.0, 0.0, -(c.max_a_dist_mps2 + 2.0), 0, 0, 0, 0};
  WeakConstraintInputs in;
  in.dt_s = 0.01;
  const auto out = Collect(x, in);
  EXPECT_DOUBLE_EQ(Find(out, WeakConstraint::kBound, kVbx)->z, c.max_v_bx_mps);
  EXPECT_DOUBLE_EQ(Find(out, WeakConstraint::kBound, kAdist)->z, -c.max_a_dist_mps2);
  // v jumped by 0.5 m/s in 10 ms (50 m/s^2 > max rate): pulled to prev + max_rate dt.
  double now[kStateSize] = {1.5, 0, 0, 0, 0, 0, 0}, prev[kStateSize] = {1.0, 0, 0, 0, 0, 0, 0};
  const auto out_r = Collect(now, in, prev);
  const PseudoMeasurement* r = Find(out_r, WeakConstraint::kRate, kVbx);
  ASSERT_NE(r, nullptr);
  EXPECT_DOUBLE_EQ(r->z, 1.0 + c.max_v_bx_rate_mps2 * 0.01);
}

}  // namespace
}  // namespace slipgraph
