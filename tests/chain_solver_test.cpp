// Levenberg-Marquardt on the chain against Ceres' own solver: the same solution on a Ward
// problem (robust losses, weak-constraint priors, the IMU offsets as the border), on a problem
// whose Gauss-Newton step overshoots (Rosenbrock), with a bound that holds at the solution, and
// the stopping rule's claim (no estimate further from the optimum than the tolerance in sd).
#include "solvers/chain_solver.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "problems/ward_batch_problem.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/chain_covariance.h"
#include "solvers/ekf_runner.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

// A Ward problem over 4 s of fig5 around the start of motion, from the EKF's estimates.
struct WardCase {
  DriveLog log;
  ModelConfig model;
  FilterResult ekf;

  WardCase() {
    log = testing::SimulatedScenario("fig5");
    testing::CutLog(&log, 2.0, 6.0);
    model = DefaultModelConfig(log.vehicle);
    ekf = RunEkf(log, model);
  }
  std::unique_ptr<WardProblem> Problem() const {
    return BuildWardBatchProblem(log, model, ekf.estimates);
  }
};

std::vector<double*> States(WardProblem* problem) {
  std::vector<double*> states;
  for (auto& x : problem->states) states.push_back(x.data());
  return states;
}

ceres::Solver::Options TightCeres() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 500;
  options.function_tolerance = options.gradient_tolerance = options.parameter_tolerance = 1e-14;
  return options;
}

class ChainSolverThreads : public ::testing::TestWithParam<int> {};

TEST_P(ChainSolverThreads, ReachesCeresSolutionOnAWardProblem) {
  const WardCase c;
  std::unique_ptr<WardProblem> chain = c.Problem(), reference = c.Problem();
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(TightCeres(), reference->problem.get(), &ceres_summary);
  ASSERT_TRUE(ceres_summary.IsSolutionUsable()) << ceres_summary.FullReport();

  ChainSolverOptions options;
  options.threads = GetParam();
  options.max_iterations = 500;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-14;
  ceres::Solver::Summary summary;
  ASSERT_TRUE(SolveOnChain(chain->problem.get(), States(chain.get()), {chain->offsets.data()},
                           options, &summary))
      << summary.message;
  EXPECT_EQ(summary.termination_type, ceres::CONVERGENCE) << summary.message;
  EXPECT_NEAR(summary.final_cost, ceres_summary.final_cost, 1e-9 * ceres_summary.final_cost);
  EXPECT_LT(summary.final_cost, summary.initial_cost);
  EXPECT_EQ(summary.iterations.size(),
            static_cast<size_t>(summary.num_successful_steps + summary.num_unsuccessful_steps + 1));

  const ChainCovariance covariance = ComputeChainCovariance(
      reference->problem.get(), States(reference.get()), {reference->offsets.data()});
  ASSERT_TRUE(covariance.ok) << covariance.error;
  double worst = 0.0;  // |chain - Ceres| in sd
  for (size_t k = 0; k < chain->states.size(); ++k) {
    for (int i = 0; i < 7; ++i) {
      const double sd = std::sqrt(covariance.states[k](i, i));
      worst = std::max(worst, std::abs(chain->states[k][i] - reference->states[k][i]) / sd);
    }
  }
  EXPECT_LT(worst, 1e-4);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(chain->offsets[i], reference->offsets[i],
                1e-4 * std::sqrt(covariance.globals(i, i)));
  }
}

INSTANTIATE_TEST_SUITE_P(OneAndTwo, ChainSolverThreads, ::testing::Values(1, 2));

// The blocks are summed in the same runs whatever the number of threads: the solution is the same
// to its last digit on one, two and three.
TEST(ChainSolver, TheSolutionDoesNotDependOnTheThreads) {
  const WardCase c;
  std::vector<std::unique_ptr<WardProblem>> solved;
  std::vector<double> final_costs;
  for (const int threads : {1, 2, 3}) {
    solved.push_back(c.Problem());
    ChainSolverOptions options;
    options.threads = threads;
    options.max_iterations = 50;
    ceres::Solver::Summary summary;
    ASSERT_TRUE(SolveOnChain(solved.back()->problem.get(), States(solved.back().get()),
                             {solved.back()->offsets.data()}, options, &summary))
        << summary.message;
    final_costs.push_back(summary.final_cost);
  }
  ASSERT_GT(solved.front()->states.size(), 64u * 2);  // more than one run of states
  for (size_t t = 1; t < solved.size(); ++t) {
    EXPECT_EQ(final_costs[t], final_costs[0]) << t + 1 << " threads";
    EXPECT_EQ(solved[t]->states, solved[0]->states) << t + 1 << " threads";
    EXPECT_EQ(solved[t]->offsets, solved[0]->offsets) << t + 1 << " threads";
  }
}

TEST(ChainSolver, StopsWithinTheToleranceInSd) {
  const WardCase c;
  std::unique_ptr<WardProblem> chain = c.Problem(), reference = c.Problem();
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(TightCeres(), reference->problem.get(), &ceres_summary);
  ChainSolverOptions options;
  options.max_iterations = 500;
  options.function_tolerance = 1e-14;
  options.step_sd_tolerance = 0.01;
  ceres::Solver::Summary summary;
  ASSERT_TRUE(SolveOnChain(chain->problem.get(), States(chain.get()), {chain->offsets.data()},
                           options, &summary));
  EXPECT_EQ(summary.termination_type, ceres::CONVERGENCE);
  EXPECT_NE(summary.message.find("sd of the solution"), std::string::npos) << summary.message;
  const ChainCovariance covariance = ComputeChainCovariance(
      reference->problem.get(), States(reference.get()), {reference->offsets.data()});
  ASSERT_TRUE(covariance.ok);
  double worst = 0.0;
  for (size_t k = 0; k < chain->states.size(); ++k) {
    for (int i = 0; i < 7; ++i) {
      const double sd = std::sqrt(covariance.states[k](i, i));
      worst = std::max(worst, std::abs(chain->states[k][i] - reference->states[k][i]) / sd);
    }
  }
  // The rule bounds the last step's length; the remaining distance is within a few of it.
  EXPECT_LT(worst, 0.05);
}

// Rosenbrock's valley as one state of a chain: the Gauss-Newton step from (-1.2, 1) raises the
// cost, so only damping reaches (1, 1).
struct Rosenbrock {
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = 10.0 * (x[1] - x[0] * x[0]);
    r[1] = 1.0 - x[0];
    return true;
  }
};

TEST(ChainSolver, DampingReachesTheMinimumOfRosenbrock) {
  std::array<double, 2> x = {-1.2, 1.0};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Rosenbrock, 2, 2>(new Rosenbrock),
                           nullptr, x.data());
  ChainSolverOptions options;
  options.max_iterations = 200;
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-14;
  options.initial_trust_region_radius = 1.0;
  ceres::Solver::Summary summary;
  ASSERT_TRUE(SolveOnChain(&problem, {x.data()}, {}, options, &summary)) << summary.message;
  EXPECT_EQ(summary.termination_type, ceres::CONVERGENCE) << summary.message;
  EXPECT_NEAR(x[0], 1.0, 1e-6);
  EXPECT_NEAR(x[1], 1.0, 1e-6);
  EXPECT_GT(summary.num_unsuccessful_steps, 0);  // the damping had work to do
}

// A chain of scalars pulled toward targets, the middle one below its lower bound: the bound
// holds, and the others settle where they would with the middle one held at the bound (that
// problem solved by Ceres without bounds; Ceres' own projection on the bounded problem stops
// 0.03 short of it here).
struct Target {
  double z;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = x[0] - z;
    return true;
  }
};
struct Smooth {
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    r[0] = 2.0 * (b[0] - a[0]);
    return true;
  }
};

TEST(ChainSolver, KeepsABoundWhereTheGradientPushesAgainstIt) {
  const std::array<double, 5> z = {1.0, 0.5, -2.0, 0.4, 1.2};
  const auto build = [&](std::array<double, 5>* x, ceres::Problem* p) {
    for (int k = 0; k < 5; ++k) {
      p->AddResidualBlock(new ceres::AutoDiffCostFunction<Target, 1, 1>(new Target{z[k]}), nullptr,
                          &(*x)[k]);
      if (k > 0) {
        p->AddResidualBlock(new ceres::AutoDiffCostFunction<Smooth, 1, 1, 1>(new Smooth), nullptr,
                            &(*x)[k - 1], &(*x)[k]);
      }
    }
  };
  std::array<double, 5> x{}, x_held{};
  x.fill(1.0);
  x_held.fill(1.0);
  x_held[2] = 0.1;
  ceres::Problem problem, held;
  build(&x, &problem);
  problem.SetParameterLowerBound(&x[2], 0, 0.1);
  build(&x_held, &held);
  held.SetParameterBlockConstant(&x_held[2]);
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(TightCeres(), &held, &ceres_summary);
  ChainSolverOptions options;
  options.max_iterations = 200;
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  std::vector<double*> states;
  for (double& v : x) states.push_back(&v);
  ASSERT_TRUE(SolveOnChain(&problem, states, {}, options, &summary)) << summary.message;
  EXPECT_EQ(summary.termination_type, ceres::CONVERGENCE) << summary.message;
  EXPECT_DOUBLE_EQ(x[2], 0.1);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(x[k], x_held[k], 1e-7) << k;
  // By hand, the left pair: 5 x0 - 4 x1 = 1, -4 x0 + 9 x1 = 0.5 + 4 * 0.1.
  EXPECT_NEAR(x[1], 1.7 / 5.8, 1e-8);
}

// A robust loss past its bend: Huber on x - 10 (its bend at 0.1) and a weak prior at 0. From 0
// the weighted J'J overstates the curvature (rho 1.5), and the step extended along the parabola
// of its two costs reaches the minimum (the prior's pull equals the residual's: x / 100 = 10 - x)
// in fewer iterations than without the extension.
struct Pull {
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = x[0] - 10.0;
    return true;
  }
};
struct WeakPrior {
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = x[0] / 10.0;
    return true;
  }
};

TEST(ChainSolver, ExtendsAStepThatGainedMoreThanPredicted) {
  int iterations[2] = {0, 0};
  for (const bool extend : {true, false}) {
    double x = 0.0;
    ceres::Problem problem;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Pull, 1, 1>(new Pull),
                             new ceres::HuberLoss(0.1), &x);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<WeakPrior, 1, 1>(new WeakPrior),
                             nullptr, &x);
    ChainSolverOptions options;
    options.max_iterations = 200;
    options.function_tolerance = 1e-16;
    options.gradient_tolerance = 1e-12;
    if (!extend) options.extrapolation_rho = 1e9;
    ceres::Solver::Summary summary;
    ASSERT_TRUE(SolveOnChain(&problem, {&x}, {}, options, &summary)) << summary.message;
    EXPECT_EQ(summary.termination_type, ceres::CONVERGENCE) << summary.message;
    EXPECT_NEAR(x, 10.0 / 1.01, 1e-8);
    EXPECT_EQ(summary.num_line_search_steps > 0, extend);
    iterations[extend ? 0 : 1] = static_cast<int>(summary.iterations.size());
  }
  EXPECT_LT(iterations[0], iterations[1]);
}

TEST(ChainSolver, InvalidOptionsAreRefused) {
  double x = 0.0;
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Pull, 1, 1>(new Pull), nullptr, &x);
  ChainSolverOptions options;
  options.threads = 0;
  ceres::Solver::Summary summary;
  EXPECT_THROW(SolveOnChain(&problem, {&x}, {}, options, &summary), std::invalid_argument);
}

TEST(ChainSolver, RefusesALinkThatSkipsAState) {
  std::array<double, 3> x = {0.0, 0.0, 0.0};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Target, 1, 1>(new Target{1.0}), nullptr,
                           &x[0]);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Smooth, 1, 1, 1>(new Smooth), nullptr,
                           &x[0], &x[2]);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Smooth, 1, 1, 1>(new Smooth), nullptr,
                           &x[1], &x[2]);
  ceres::Solver::Summary summary;
  EXPECT_FALSE(SolveOnChain(&problem, {&x[0], &x[1], &x[2]}, {}, ChainSolverOptions(), &summary));
  EXPECT_EQ(summary.termination_type, ceres::FAILURE);
  EXPECT_NE(summary.message.find("not a chain"), std::string::npos) << summary.message;
  EXPECT_EQ(x[0], 0.0);  // nothing moved
}

}  // namespace
}  // namespace slipgraph
