// ComponentAutoDiffCostFunction against Ceres' AutoDiffCostFunction over whole blocks, for every
// factor that uses it: the same residuals and Jacobians at random states. A component list that
// misses one the functor reads fails this check (the last test shows it would).
#include "factors/component_autodiff.h"

#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "factors/at_rest_prior.h"
#include "factors/bound_prior.h"
#include "factors/disturbance_decay_prior.h"
#include "factors/encoder_factor.h"
#include "factors/gnss_velocity_factor.h"
#include "factors/imu_factor.h"
#include "factors/oppose_motion_prior.h"
#include "factors/rate_bound_prior.h"
#include "tests/factor_check.h"

namespace slipgraph {
namespace {

// Residuals and Jacobians of `a` and `b` at `n` random points (blocks of the given sizes, values
// spread over [-scale, scale]) agree to `tolerance`.
void ExpectSameEvaluations(const ceres::CostFunction& a, const ceres::CostFunction& b,
                           double scale = 3.0, int n = 50, double tolerance = 1e-12) {
  ASSERT_EQ(a.num_residuals(), b.num_residuals());
  ASSERT_EQ(a.parameter_block_sizes(), b.parameter_block_sizes());
  const std::vector<int32_t>& sizes = a.parameter_block_sizes();
  const int rows = a.num_residuals();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-scale, scale);
  for (int trial = 0; trial < n; ++trial) {
    std::vector<std::vector<double>> blocks;
    std::vector<const double*> parameters;
    std::vector<std::vector<double>> ja, jb;
    std::vector<double*> pa, pb;
    for (const int size : sizes) {
      blocks.emplace_back(size);
      for (double& v : blocks.back()) v = value(rng);
      ja.emplace_back(static_cast<size_t>(rows) * size, -99.0);  // every entry must be written
      jb.emplace_back(static_cast<size_t>(rows) * size, -99.0);
    }
    for (size_t i = 0; i < sizes.size(); ++i) {
      parameters.push_back(blocks[i].data());
      pa.push_back(ja[i].data());
      pb.push_back(jb[i].data());
    }
    std::vector<double> ra(rows), rb(rows), plain(rows);
    ASSERT_TRUE(a.Evaluate(parameters.data(), ra.data(), pa.data()));
    ASSERT_TRUE(b.Evaluate(parameters.data(), rb.data(), pb.data()));
    ASSERT_TRUE(a.Evaluate(parameters.data(), plain.data(), nullptr));
    for (int r = 0; r < rows; ++r) {
      EXPECT_NEAR(ra[r], rb[r], tolerance);
      EXPECT_NEAR(plain[r], ra[r], tolerance * std::max(1.0, std::abs(ra[r])));
    }
    for (size_t i = 0; i < sizes.size(); ++i) {
      for (size_t k = 0; k < ja[i].size(); ++k) {
        EXPECT_NEAR(ja[i][k], jb[i][k], tolerance) << "block " << i << " entry " << k;
      }
    }
  }
}

constexpr int kX = ward::kStateSize;

TEST(ComponentAutoDiff, EncoderFactor) {
  const std::unique_ptr<ceres::CostFunction> f(EncoderFactor::Create(4.1, -0.3, 0.05));
  ceres::AutoDiffCostFunction<EncoderFactor, 2, kX> full(new EncoderFactor(4.1, -0.3, 0.05));
  ExpectSameEvaluations(*f, full);
}

TEST(ComponentAutoDiff, GnssVelocityFactor) {
  const std::unique_ptr<ceres::CostFunction> f(GnssVelocityFactor::Create(0.7, 0.1));
  ceres::AutoDiffCostFunction<GnssVelocityFactor, 1, kX> full(new GnssVelocityFactor(0.7, 0.1));
  ExpectSameEvaluations(*f, full);
}

TEST(ComponentAutoDiff, YawGyroFactor) {
  const std::unique_ptr<ceres::CostFunction> f(YawGyroFactor::Create(0.2, 0.005));
  ceres::AutoDiffCostFunction<YawGyroFactor, 1, kX, 2> full(new YawGyroFactor(0.2, 0.005));
  ExpectSameEvaluations(*f, full);
}

// The offsets held constant (no Jacobian asked for their block): the state's Jacobian alone,
// the same as with both.
TEST(ComponentAutoDiff, ABlockWithoutItsJacobian) {
  const std::unique_ptr<ceres::CostFunction> f(YawGyroFactor::Create(0.2, 0.005));
  const double x[kX] = {1.0, 0.0, 0.0, 4.0, 4.0, 0.3, 0.002};
  const double offsets[2] = {0.1, 0.01};
  const double* parameters[2] = {x, offsets};
  double r_one, r_both, j_state[kX], j_both_state[kX], j_offsets[2];
  double* one[2] = {j_state, nullptr};
  double* both[2] = {j_both_state, j_offsets};
  ASSERT_TRUE(f->Evaluate(parameters, &r_one, one));
  ASSERT_TRUE(f->Evaluate(parameters, &r_both, both));
  EXPECT_EQ(r_one, r_both);
  for (int i = 0; i < kX; ++i) EXPECT_EQ(j_state[i], j_both_state[i]);
  EXPECT_EQ(j_offsets[0], 0.0);
  EXPECT_NE(j_offsets[1], 0.0);
}

TEST(ComponentAutoDiff, DisturbanceDecayAndOpposeMotionPriors) {
  const std::unique_ptr<ceres::CostFunction> decay(DisturbanceDecayPrior::Create(0.3));
  ceres::AutoDiffCostFunction<DisturbanceDecayPrior, 1, kX> full_decay(
      new DisturbanceDecayPrior(0.3));
  ExpectSameEvaluations(*decay, full_decay);
  for (const double direction : {1.0, -1.0}) {
    const std::unique_ptr<ceres::CostFunction> oppose(OpposeMotionPrior::Create(direction, 0.2));
    ceres::AutoDiffCostFunction<OpposeMotionPrior, 1, kX> full_oppose(
        new OpposeMotionPrior(direction, 0.2));
    ExpectSameEvaluations(*oppose, full_oppose);
  }
}

TEST(ComponentAutoDiff, BoundAndAtRestPriors) {
  const std::array<double, 4> bounds{3.0, 0.5, 2.0, 0.1};
  const std::unique_ptr<ceres::CostFunction> bound(BoundPrior::Create(bounds, 0.1));
  ceres::AutoDiffCostFunction<BoundPrior, 4, kX> full_bound(new BoundPrior(bounds, 0.1));
  ExpectSameEvaluations(*bound, full_bound);
  const std::unique_ptr<ceres::CostFunction> rest(AtRestPrior::Create(0.01, 0.001));
  ceres::AutoDiffCostFunction<AtRestPrior, 3, kX> full_rest(new AtRestPrior(0.01, 0.001));
  ExpectSameEvaluations(*rest, full_rest);
}

TEST(ComponentAutoDiff, RateBoundPriorOnTwoStates) {
  // Values within a few limits of each other, so that both the flat and the linear part count.
  const std::unique_ptr<ceres::CostFunction> f(RateBoundPrior::Create({5.0, 0.5}, 0.01, 0.5));
  ceres::AutoDiffCostFunction<RateBoundPrior, 2, kX, kX> full(
      new RateBoundPrior({5.0, 0.5}, 0.01, 0.5));
  ExpectSameEvaluations(*f, full, 0.05);
  ExpectSameEvaluations(*f, full, 3.0);
  // And against numeric differentiation, past the rate limit on v_bx and inside it on b_ax.
  const double x[kX] = {1.0, 0.02, 0.0, 4.0, 4.0, 0.0, 0.0};
  const double x_next[kX] = {1.1, 0.021, 0.0, 4.0, 4.0, 0.0, 0.0};
  testing::ExpectJacobiansMatchNumeric(*f, {x, x_next});
}

// A list that leaves out a component the functor reads: its column reads zero, and the check
// above sees it.
struct ReadsOnlyTheLeftWheel {
  static constexpr std::array<BlockComponent, 1> kComponents{{{0, ward::kOmegaLeft}}};
};

TEST(ComponentAutoDiff, AMissingComponentIsCaughtByTheCheck) {
  ComponentAutoDiffCostFunction<EncoderFactor, ReadsOnlyTheLeftWheel, 2, kX> wrong(
      new EncoderFactor(4.1, -0.3, 0.05));
  ceres::AutoDiffCostFunction<EncoderFactor, 2, kX> full(new EncoderFactor(4.1, -0.3, 0.05));
  const double x[kX] = {1.0, 0.0, 0.0, 4.0, 4.2, 0.0, 0.0};
  const double* parameters[1] = {x};
  double r[2], jw[2 * kX], jf[2 * kX];
  double* pw[1] = {jw};
  double* pf[1] = {jf};
  ASSERT_TRUE(wrong.Evaluate(parameters, r, pw));
  ASSERT_TRUE(full.Evaluate(parameters, r, pf));
  EXPECT_EQ(jw[1 * kX + ward::kOmegaRight], 0.0);
  EXPECT_NE(jf[1 * kX + ward::kOmegaRight], 0.0);
}

}  // namespace
}  // namespace slipgraph
