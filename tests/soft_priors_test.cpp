// Soft priors of the smoother: first-state and offset priors, the disturbance random walk and
// decay (WC2), the wheel-speed walk, oppose-motion (WC1), at-rest (WC4) and bounds (WC5).
#include <gtest/gtest.h>

#include <memory>

#include "factors/at_rest_prior.h"
#include "factors/bound_prior.h"
#include "factors/diagonal_prior.h"
#include "factors/disturbance_decay_prior.h"
#include "factors/no_pull_back_prior.h"
#include "factors/oppose_motion_prior.h"
#include "factors/state_walk_factor.h"
#include "tests/factor_check.h"

namespace slipgraph {
namespace {

using namespace ward;  // NOLINT

TEST(DiagonalPrior, ResidualIsTheNormalizedDifference) {
  const std::unique_ptr<ceres::CostFunction> f(DiagonalPrior<2>::Create({1.0, 2.0}, {0.5, 0.1}));
  const double x[2] = {2.0, 2.0};
  const std::vector<double> r = testing::Residuals(*f, {x});
  EXPECT_DOUBLE_EQ(r[0], 2.0);
  EXPECT_DOUBLE_EQ(r[1], 0.0);
  testing::ExpectJacobiansMatchNumeric(*f, {x});
}

TEST(DisturbanceFactors, WalkAndDecay) {
  const double a[kStateSize] = {0, 0, -1.0, 0, 0, 0, 0};
  const double b[kStateSize] = {0, 0, -2.5, 0, 0, 0, 0};
  const std::unique_ptr<ceres::CostFunction> walk(DisturbanceWalkFactor::Create(0.5));
  EXPECT_DOUBLE_EQ(testing::Residuals(*walk, {a, b})[0], -3.0);
  testing::ExpectJacobiansMatchNumeric(*walk, {a, b});
  const std::unique_ptr<ceres::CostFunction> decay(DisturbanceDecayPrior::Create(2.0));
  EXPECT_DOUBLE_EQ(testing::Residuals(*decay, {b})[0], -1.25);
  testing::ExpectJacobiansMatchNumeric(*decay, {b});
}

TEST(WheelSpeedWalkFactor, BothWheelsIncrementsOnly) {
  const double a[kStateSize] = {1.0, 0, -1.0, 4.0, 5.0, 0.2, 0};
  const double b[kStateSize] = {2.0, 0.1, 3.0, 4.5, 4.0, 0.7, 0.01};
  const std::unique_ptr<ceres::CostFunction> walk(WheelSpeedWalkFactor::Create(0.25));
  const std::vector<double> r = testing::Residuals(*walk, {a, b});
  EXPECT_DOUBLE_EQ(r[0], 2.0);   // (4.5 - 4.0) / 0.25
  EXPECT_DOUBLE_EQ(r[1], -4.0);  // (4.0 - 5.0) / 0.25
  testing::ExpectJacobiansMatchNumeric(*walk, {a, b});
}

TEST(OpposeMotionPrior, PenalizesOnlyAPushingDisturbance) {
  const std::unique_ptr<ceres::CostFunction> forward(OpposeMotionPrior::Create(1.0, 0.5));
  const double resisting[kStateSize] = {1, 0, -1.0, 4, 4, 0, 0};
  const double pushing[kStateSize] = {1, 0, 1.0, 4, 4, 0, 0};
  const double zero[kStateSize] = {1, 0, 0.0, 4, 4, 0, 0};
  EXPECT_NEAR(testing::Residuals(*forward, {resisting})[0], 0.0, 1e-4);
  EXPECT_NEAR(testing::Residuals(*forward, {pushing})[0], 1.0 / 0.5, 1e-4);
  // Smooth at the kink: residual eps/2 / sd at zero, Jacobians finite and correct there.
  EXPECT_NEAR(testing::Residuals(*forward, {zero})[0], 0.5 * OpposeMotionPrior::kEpsMps2 / 0.5,
              1e-12);
  for (const double* x : {resisting, pushing, zero}) {
    testing::ExpectJacobiansMatchNumeric(*forward, {x});
  }
  const std::unique_ptr<ceres::CostFunction> reverse(OpposeMotionPrior::Create(-1.0, 0.5));
  EXPECT_NEAR(testing::Residuals(*reverse, {resisting})[0], 1.0 / 0.5, 1e-4);
}

TEST(NoPullBackPrior, PenalizesOnlyAVelocityAgainstTheWheels) {
  const std::unique_ptr<ceres::CostFunction> forward(NoPullBackPrior::Create(1.0, 0.05));
  const double along[kStateSize] = {0.5, 0, -2.0, 4, 4, 0, 0};
  const double against[kStateSize] = {-0.1, 0, -2.0, 4, 4, 0, 0};
  const double still[kStateSize] = {0.0, 0, -2.0, 4, 4, 0, 0};
  EXPECT_NEAR(testing::Residuals(*forward, {along})[0], 0.0, 1e-3);
  EXPECT_NEAR(testing::Residuals(*forward, {against})[0], 0.1 / 0.05, 1e-3);
  // Smooth at the kink: residual eps/2 / sd at zero, Jacobians finite and correct there.
  EXPECT_NEAR(testing::Residuals(*forward, {still})[0], 0.5 * NoPullBackPrior::kEpsMps / 0.05,
              1e-12);
  for (const double* x : {along, against, still}) {
    testing::ExpectJacobiansMatchNumeric(*forward, {x}, 1e-4);
  }
  const std::unique_ptr<ceres::CostFunction> reverse(NoPullBackPrior::Create(-1.0, 0.05));
  EXPECT_NEAR(testing::Residuals(*reverse, {along})[0], 0.5 / 0.05, 1e-3);
  EXPECT_NEAR(testing::Residuals(*reverse, {against})[0], 0.0, 1e-3);
}

TEST(AtRestPrior, PullsBiasesAndDisturbanceToZero) {
  const std::unique_ptr<ceres::CostFunction> f(AtRestPrior::Create(0.1, 0.01));
  const double x[kStateSize] = {0, 0.02, -0.3, 0, 0, 0, 0.001};
  const std::vector<double> r = testing::Residuals(*f, {x});
  EXPECT_DOUBLE_EQ(r[0], 0.2);
  EXPECT_DOUBLE_EQ(r[1], -3.0);
  EXPECT_DOUBLE_EQ(r[2], 0.1);
  testing::ExpectJacobiansMatchNumeric(*f, {x});
}

TEST(BoundPrior, ZeroInsideLinearOutside) {
  const std::unique_ptr<ceres::CostFunction> f(BoundPrior::Create({3.0, 0.5, 10.0, 0.1}, 0.1));
  const double inside[kStateSize] = {1.0, 0.1, -2.0, 0, 0, 0, 0.01};
  const double outside[kStateSize] = {-4.0, 0.1, -2.0, 0, 0, 0, 0.01};
  for (double r : testing::Residuals(*f, {inside})) EXPECT_NEAR(r, 0.0, 1e-3);
  EXPECT_NEAR(testing::Residuals(*f, {outside})[0], (4.0 - 3.0) / 0.1, 1e-2);
  // Inside the bounds the derivatives are ~1e-8 (the hinge's tail); the numeric side's absolute
  // error there (~1e-13) is 2e-5 relative, hence the looser precision.
  testing::ExpectJacobiansMatchNumeric(*f, {inside}, 1e-4);
  testing::ExpectJacobiansMatchNumeric(*f, {outside}, 1e-4);
}

}  // namespace
}  // namespace slipgraph

#include "factors/rate_bound_prior.h"

namespace slipgraph {
namespace {

TEST(RateBoundPrior, PenalizesOnlyChangesFasterThanTheLimit) {
  // v_bx limited to 5 m/s^2, b_ax to 0.5 m/s^3, over dt = 0.01 s.
  const std::unique_ptr<ceres::CostFunction> f(RateBoundPrior::Create({5.0, 0.5}, 0.01, 0.5));
  const double a[ward::kStateSize] = {1.0, 0.0, 0, 0, 0, 0, 0};
  const double slow[ward::kStateSize] = {1.02, 0.001, 0, 0, 0, 0, 0};  // 2 m/s^2, 0.1 m/s^3
  const double fast[ward::kStateSize] = {0.92, 0.0, 0, 0, 0, 0, 0};    // -8 m/s^2
  EXPECT_NEAR(testing::Residuals(*f, {a, slow})[0], 0.0, 1e-3);
  EXPECT_NEAR(testing::Residuals(*f, {a, slow})[1], 0.0, 1e-3);
  // |rate| 8 over the limit 5: (8 - 5) / 0.5 = 6 (the smoothing shifts it by < 1e-3).
  EXPECT_NEAR(testing::Residuals(*f, {a, fast})[0], 6.0, 2e-3);
  for (const double* b : {slow, fast}) testing::ExpectJacobiansMatchNumeric(*f, {a, b}, 1e-5);
}

}  // namespace
}  // namespace slipgraph
