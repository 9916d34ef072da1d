#include "solvers/model_choice_variance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace slipgraph {
namespace {

// A state with only its velocity set.
WardEstimate State(double t_s, double v_mps, double sd_v_mps) {
  WardEstimate e;
  e.t = t_s;
  e.x[ward::kVbx] = v_mps;
  e.sd[ward::kVbx] = sd_v_mps;
  return e;
}

TEST(ModelChoiceVariance, ProbabilityFromTheLikelihoodRatio) {
  EXPECT_DOUBLE_EQ(OtherModelProbability(0.0), 0.5);
  EXPECT_NEAR(OtherModelProbability(3.0), 1.0 / (1.0 + std::exp(-3.0)), 1e-15);
  EXPECT_NEAR(OtherModelProbability(-3.0), std::exp(-3.0) / (1.0 + std::exp(-3.0)), 1e-15);
  EXPECT_EQ(OtherModelProbability(-1e4), 0.0);  // no overflow in either tail
  EXPECT_EQ(OtherModelProbability(1e4), 1.0);
  EXPECT_THROW(OtherModelProbability(std::nan("")), std::invalid_argument);
}

TEST(ModelChoiceVariance, ByHand) {
  std::vector<WardEstimate> kept = {State(0.0, 1.0, 0.03), State(0.01, 2.0, 0.04)};
  const std::vector<WardEstimate> other = {State(0.0, 1.1, 0.01), State(0.01, 2.0, 0.01)};
  AddModelChoiceVariance(other, 0.25, &kept);
  EXPECT_NEAR(kept[0].sd[ward::kVbx], std::sqrt(0.03 * 0.03 + 0.25 * 0.1 * 0.1), 1e-15);
  // The same solution: the sd unchanged, not narrowed by the other model's smaller one.
  EXPECT_NEAR(kept[1].sd[ward::kVbx], 0.04, 1e-15);
  EXPECT_EQ(kept[0].x[ward::kVbx], 1.0);  // the estimates unchanged
  // p_other = 0: nothing changes.
  std::vector<WardEstimate> again = {State(0.0, 1.0, 0.03)};
  AddModelChoiceVariance({State(0.0, 5.0, 1.0)}, 0.0, &again);
  EXPECT_EQ(again[0].sd[ward::kVbx], 0.03);
}

// The sd is the kept solution's root mean squared error when the truth is, with probability
// p_other, at the other solution and otherwise at the kept one, spread by the kept one's sd: the
// variance's claim, checked by sampling.
TEST(ModelChoiceVariance, IsTheMeanSquaredErrorOverBothModels) {
  const double p_other = 0.3, x_kept = 0.0, sd_kept = 0.02, x_other = -0.05;
  std::vector<WardEstimate> kept = {State(0.0, x_kept, sd_kept)};
  AddModelChoiceVariance({State(0.0, x_other, 0.001)}, p_other, &kept);
  std::mt19937_64 rng(7);
  std::bernoulli_distribution pick(p_other);
  std::normal_distribution<double> normal;
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double truth = (pick(rng) ? x_other : x_kept) + sd_kept * normal(rng);
    sum += (truth - x_kept) * (truth - x_kept);
  }
  // The sampled root mean square has a relative standard error of about 0.2 % here; 1 % is five
  // of them, and a formula that left out p_other or mixed in the other's sd is off by 5 % or more.
  EXPECT_NEAR(std::sqrt(sum / n), kept[0].sd[ward::kVbx], 0.01 * kept[0].sd[ward::kVbx]);
}

TEST(ModelChoiceVariance, MismatchedSolutionsAreRefused) {
  std::vector<WardEstimate> kept = {State(0.0, 1.0, 0.1)};
  EXPECT_THROW(AddModelChoiceVariance({}, 0.5, &kept), std::invalid_argument);
  EXPECT_THROW(AddModelChoiceVariance({State(0.5, 1.0, 0.1)}, 0.5, &kept), std::invalid_argument);
  EXPECT_THROW(AddModelChoiceVariance({State(0.0, 1.0, 0.1)}, 1.5, &kept), std::invalid_argument);
}

}  // namespace
}  // namespace slipgraph
