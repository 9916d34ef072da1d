// Marginalization (Schur complement into a MarginalPrior) against the full problem's solution on
// small chains: exact for a linear-Gaussian chain, close for a mildly nonlinear one.
#include "solvers/marginalization.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <random>

namespace slipgraph {
namespace {

// A 2-state chain with a shared 1-parameter block g (like the IMU offsets):
//   x_{k+1} = f(x_k) + [g, 0] + noise,   z_k = x_k[0] + g + noise.
struct Step {
  double dt;
  double nonlinearity;  // 0: linear chain
  template <typename T>
  bool operator()(const T* x, const T* y, const T* g, T* r) const {
    r[0] = (y[0] - (x[0] + dt * x[1] + nonlinearity * sin(x[0]) + g[0])) / 0.05;
    r[1] = (y[1] - (x[1] + nonlinearity * 0.1 * x[0] * x[1])) / 0.1;
    return true;
  }
};
struct Observation {
  double z;
  template <typename T>
  bool operator()(const T* x, const T* g, T* r) const {
    r[0] = (x[0] + g[0] - z) / 0.2;
    return true;
  }
};
struct Prior {
  std::array<double, 2> mean;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = (x[0] - mean[0]) / 1.0;
    r[1] = (x[1] - mean[1]) / 1.0;
    return true;
  }
};
struct GPrior {
  template <typename T>
  bool operator()(const T* g, T* r) const {
    r[0] = g[0] / 0.5;
    return true;
  }
};

struct Chain {
  std::vector<double> z;
  double nonlinearity;
};

Chain MakeChain(int n, double nonlinearity) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.2);
  Chain c{{}, nonlinearity};
  double x0 = 0.0, x1 = 1.0;
  for (int k = 0; k < n; ++k) {
    c.z.push_back(x0 + 0.3 + noise(rng));
    x0 += 0.1 * x1 + nonlinearity * std::sin(x0) + 0.3;
    x1 += nonlinearity * 0.1 * x0 * x1;
  }
  return c;
}

ceres::Solver::Options Exact() {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = 100;
  o.function_tolerance = o.gradient_tolerance = o.parameter_tolerance = 1e-15;
  o.logging_type = ceres::SILENT;
  return o;
}

void AddStepFactors(const Chain& c, int k, double* previous, double* x, double* g,
                    ceres::Problem* problem) {
  problem->AddResidualBlock(
      new ceres::AutoDiffCostFunction<Observation, 1, 2, 1>(new Observation{c.z[k]}), nullptr, x,
      g);
  if (previous != nullptr) {
    problem->AddResidualBlock(
        new ceres::AutoDiffCostFunction<Step, 2, 2, 2, 1>(new Step{0.1, c.nonlinearity}), nullptr,
        previous, x, g);
  }
}

// Full problem: every state; returns the last `keep` states and g.
std::vector<std::array<double, 2>> SolveFull(const Chain& c, int keep, double* g_out) {
  const int n = static_cast<int>(c.z.size());
  std::vector<std::array<double, 2>> x(n, {0.0, 1.0});
  double g = 0.0;
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Prior, 2, 2>(new Prior{{0.0, 1.0}}),
                           nullptr, x[0].data());
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<GPrior, 1, 1>(new GPrior), nullptr, &g);
  for (int k = 0; k < n; ++k) {
    AddStepFactors(c, k, k > 0 ? x[k - 1].data() : nullptr, x[k].data(), &g, &problem);
  }
  ceres::Solver::Summary summary;
  ceres::Solve(Exact(), &problem, &summary);
  *g_out = g;
  return {x.end() - keep, x.end()};
}

// Sliding window of `window` states, solved after each new state, oldest marginalized.
std::vector<std::array<double, 2>> SolveWindowed(const Chain& c, int window, double* g_out) {
  ceres::Problem::Options options;
  options.enable_fast_removal = true;
  ceres::Problem problem(options);
  std::deque<std::array<double, 2>> x;
  double g = 0.0;
  x.push_back({0.0, 1.0});
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Prior, 2, 2>(new Prior{{0.0, 1.0}}),
                           nullptr, x[0].data());
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<GPrior, 1, 1>(new GPrior), nullptr, &g);
  AddStepFactors(c, 0, nullptr, x[0].data(), &g, &problem);
  for (int k = 1; k < static_cast<int>(c.z.size()); ++k) {
    x.push_back(x.back());
    AddStepFactors(c, k, x[x.size() - 2].data(), x.back().data(), &g, &problem);
    ceres::Solver::Summary summary;
    ceres::Solve(Exact(), &problem, &summary);
    if (static_cast<int>(x.size()) > window) {
      Marginalization m = Marginalize(problem, {x.front().data()});
      EXPECT_TRUE(m.prior) << m.error;
      problem.RemoveParameterBlock(x.front().data());
      problem.AddResidualBlock(m.prior.release(), nullptr, m.kept);
      x.pop_front();
    }
  }
  ceres::Solver::Summary summary;
  ceres::Solve(Exact(), &problem, &summary);
  *g_out = g;
  return {x.begin(), x.end()};
}

TEST(Marginalization, LinearChainMatchesTheFullProblemExactly) {
  const Chain c = MakeChain(40, 0.0);
  double g_full = 0.0, g_window = 0.0;
  const auto full = SolveFull(c, 5, &g_full);
  const auto window = SolveWindowed(c, 5, &g_window);
  ASSERT_EQ(window.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    // Equal up to the solver's convergence on a weakly observed chain (velocity seen only
    // through 40 positions): 1e-6, three orders below the nonlinear case's gap.
    EXPECT_NEAR(window[i][0], full[i][0], 1e-6);
    EXPECT_NEAR(window[i][1], full[i][1], 1e-6);
  }
  EXPECT_NEAR(g_window, g_full, 1e-6);
}

TEST(Marginalization, NonlinearChainStaysCloseToTheFullProblem) {
  const Chain c = MakeChain(40, 0.02);
  double g_full = 0.0, g_window = 0.0;
  const auto full = SolveFull(c, 5, &g_full);
  const auto window = SolveWindowed(c, 5, &g_window);
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(window[i][0], full[i][0], 2e-3);
    EXPECT_NEAR(window[i][1], full[i][1], 2e-3);
  }
  EXPECT_NEAR(g_window, g_full, 2e-3);
}

TEST(Marginalization, DroppingInsteadOfMarginalizingLosesInformation) {
  // The control: without the prior, the window's answer moves away from the full solution.
  const Chain c = MakeChain(40, 0.0);
  double g_full = 0.0;
  const auto full = SolveFull(c, 5, &g_full);
  ceres::Problem problem;
  std::vector<std::array<double, 2>> x(5, {0.0, 1.0});
  double g = 0.0;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<GPrior, 1, 1>(new GPrior), nullptr, &g);
  for (int i = 0; i < 5; ++i) {
    AddStepFactors(c, 35 + i, i > 0 ? x[i - 1].data() : nullptr, x[i].data(), &g, &problem);
  }
  ceres::Solver::Summary summary;
  ceres::Solve(Exact(), &problem, &summary);
  EXPECT_GT(std::abs(g - g_full), 1e-3);
}

// The prior is the same to the bit whatever the order the factors went in and wherever the
// blocks sit in memory: the problem hands out a block's residual blocks by address, and sums in
// that order differ in their last bits from one run or build to the next.
TEST(Marginalization, ThePriorDoesNotDependOnTheOrderOrAddressOfItsFactors) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> z(12);
  for (double& v : z) v = noise(rng);
  const auto marginalize = [&](bool reversed, std::vector<std::array<double, 2>>* storage,
                               std::vector<double>* g_storage) {
    // Leaving block a, kept blocks b and g; six observations and two steps touch a.
    ceres::Problem::Options options;
    options.enable_fast_removal = true;
    ceres::Problem problem(options);
    double* a = (*storage)[reversed ? 2 : 0].data();
    double* b = (*storage)[1].data();
    double* g = &(*g_storage)[reversed ? 3 : 0];
    std::vector<std::function<void()>> adds;
    for (int i = 0; i < 6; ++i) {
      adds.push_back([&, i] {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<Observation, 1, 2, 1>(new Observation{z[i]}), nullptr,
            a, g);
      });
    }
    for (int i = 0; i < 2; ++i) {
      adds.push_back([&, i] {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<Step, 2, 2, 2, 1>(new Step{0.1 * (i + 1), 0.02}),
            nullptr, a, b, g);
      });
    }
    if (reversed) std::reverse(adds.begin(), adds.end());
    for (const auto& add : adds) add();
    return Marginalize(problem, {a});
  };
  std::vector<std::array<double, 2>> first(3, {0.3, -0.2}), second(3, {0.3, -0.2});
  std::vector<double> g_first(4, 0.05), g_second(4, 0.05);
  const Marginalization m1 = marginalize(false, &first, &g_first);
  const Marginalization m2 = marginalize(true, &second, &g_second);
  ASSERT_TRUE(m1.prior && m2.prior) << m1.error << m2.error;
  ASSERT_EQ(m1.kept.size(), 2u);
  ASSERT_EQ(m2.kept.size(), 2u);
  // The same kept blocks in the same order: b first or g first in both.
  ASSERT_EQ(m1.kept[0] == first[1].data(), m2.kept[0] == second[1].data());
  const int rows = m1.prior->num_residuals();
  ASSERT_EQ(rows, m2.prior->num_residuals());
  std::vector<double> r1(rows), r2(rows), j1b(rows * 2), j2b(rows * 2), j1g(rows), j2g(rows);
  const bool b_first = m1.kept[0] == first[1].data();
  double* j1[2] = {b_first ? j1b.data() : j1g.data(), b_first ? j1g.data() : j1b.data()};
  double* j2[2] = {b_first ? j2b.data() : j2g.data(), b_first ? j2g.data() : j2b.data()};
  const double* p1[2] = {m1.kept[0], m1.kept[1]};
  const double* p2[2] = {m2.kept[0], m2.kept[1]};
  ASSERT_TRUE(m1.prior->Evaluate(p1, r1.data(), j1));
  ASSERT_TRUE(m2.prior->Evaluate(p2, r2.data(), j2));
  for (int i = 0; i < rows; ++i) EXPECT_EQ(r1[i], r2[i]) << i;
  for (int i = 0; i < rows * 2; ++i) EXPECT_EQ(j1b[i], j2b[i]) << i;
  for (int i = 0; i < rows; ++i) EXPECT_EQ(j1g[i], j2g[i]) << i;
}

TEST(Marginalization, ReportsABlockThatCannotBeEvaluated) {
  ceres::Problem::Options options;
  options.enable_fast_removal = true;
  ceres::Problem problem(options);
  std::array<double, 2> a{std::nan(""), 0.0}, b{0.0, 0.0};
  double g = 0.0;
  const Chain c = MakeChain(2, 0.0);
  AddStepFactors(c, 0, nullptr, a.data(), &g, &problem);
  AddStepFactors(c, 1, a.data(), b.data(), &g, &problem);
  const Marginalization m = Marginalize(problem, {a.data()});
  EXPECT_FALSE(m.prior);
  EXPECT_FALSE(m.error.empty());
}

// A block whose factors reach no other block (the IPD window's block after a recalled terrain
// model replaced the walk out of it) leaves nothing to carry: no prior, and no failure.
TEST(Marginalization, ABlockThatTouchesNothingKeptLeavesNoPriorAndNoError) {
  ceres::Problem::Options options;
  options.enable_fast_removal = true;
  ceres::Problem problem(options);
  std::array<double, 2> a{1.0, 2.0}, b{0.0, 0.0};
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Prior, 2, 2>(new Prior{{0.5, 0.5}}),
                           nullptr, a.data());
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Prior, 2, 2>(new Prior{{0.0, 0.0}}),
                           nullptr, b.data());
  const Marginalization m = Marginalize(problem, {a.data()});
  EXPECT_FALSE(m.prior);
  EXPECT_TRUE(m.kept.empty());
  EXPECT_TRUE(m.error.empty()) << m.error;
}

}  // namespace
}  // namespace slipgraph
