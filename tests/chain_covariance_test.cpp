// ChainCovariance against ceres::Covariance on the Ward problem of a short simulated log, and
// its refusal of a problem that is not a chain.
#include "solvers/chain_covariance.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/covariance.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "problems/ward_batch_problem.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {
namespace {

TEST(ChainCovariance, MatchesCeresCovarianceOnAWardProblem) {
  const sim::ScenarioRun run = sim::ExpandScenario("fig5", 1).at(0);
  DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  // 4 s around the start of motion: 400 states, small enough for SPARSE_QR.
  const auto cut = [](auto* samples) {
    samples->erase(std::remove_if(samples->begin(), samples->end(),
                                  [](const auto& s) { return s.t < 2.0 || s.t > 6.0; }),
                   samples->end());
  };
  cut(&log.wheels);
  cut(&log.imu);
  cut(&log.gps);
  cut(&log.attitude);
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  const FilterResult ekf = RunEkf(log, model);
  std::unique_ptr<WardProblem> problem = BuildWardBatchProblem(log, model, ekf.estimates);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  ceres::Solver::Summary summary;
  ceres::Solve(options, problem->problem.get(), &summary);

  std::vector<double*> states;
  for (auto& x : problem->states) states.push_back(x.data());
  const ChainCovariance chain =
      ComputeChainCovariance(problem->problem.get(), states, {problem->offsets.data()});
  ASSERT_TRUE(chain.ok) << chain.error;

  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::SPARSE_QR;
  ceres::Covariance covariance(covariance_options);
  std::vector<std::pair<const double*, const double*>> blocks;
  for (size_t k = 0; k < states.size(); k += 37) blocks.emplace_back(states[k], states[k]);
  for (size_t k = 0; k + 1 < states.size(); k += 37) blocks.emplace_back(states[k + 1], states[k]);
  blocks.emplace_back(problem->offsets.data(), problem->offsets.data());
  ASSERT_TRUE(covariance.Compute(blocks, problem->problem.get()));
  for (size_t k = 0; k < states.size(); k += 37) {
    Eigen::Matrix<double, 7, 7, Eigen::RowMajor> expected;
    covariance.GetCovarianceBlock(states[k], states[k], expected.data());
    for (int i = 0; i < 7; ++i) {
      for (int j = 0; j < 7; ++j) {
        const double scale = std::sqrt(expected(i, i) * expected(j, j));
        EXPECT_NEAR(chain.states[k](i, j), expected(i, j), 1e-6 * scale)
            << "state " << k << " (" << i << ", " << j << ")";
      }
    }
  }
  // Consecutive states' cross-covariance, cov(x_{k+1}, x_k), with the border correction.
  ASSERT_EQ(chain.next.size(), states.size() - 1);
  for (size_t k = 0; k + 1 < states.size(); k += 37) {
    Eigen::Matrix<double, 7, 7, Eigen::RowMajor> expected;
    covariance.GetCovarianceBlock(states[k + 1], states[k], expected.data());
    for (int i = 0; i < 7; ++i) {
      for (int j = 0; j < 7; ++j) {
        const double scale = std::sqrt(chain.states[k + 1](i, i) * chain.states[k](j, j));
        EXPECT_NEAR(chain.next[k](i, j), expected(i, j), 1e-6 * scale)
            << "pair " << k << " (" << i << ", " << j << ")";
      }
    }
  }
  Eigen::Matrix<double, 2, 2, Eigen::RowMajor> offsets;
  covariance.GetCovarianceBlock(problem->offsets.data(), problem->offsets.data(), offsets.data());
  EXPECT_NEAR(chain.globals(0, 0), offsets(0, 0), 1e-6 * offsets(0, 0));
  EXPECT_NEAR(chain.globals(1, 1), offsets(1, 1), 1e-6 * offsets(1, 1));
}

struct Link {
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    r[0] = b[0] - a[0];
    return true;
  }
};
struct Anchor {
  template <typename T>
  bool operator()(const T* a, T* r) const {
    r[0] = a[0];
    return true;
  }
};

TEST(ChainCovariance, RefusesALinkThatSkipsAState) {
  ceres::Problem problem;
  double x[3] = {0.0, 0.0, 0.0};
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Anchor, 1, 1>(new Anchor), nullptr, x);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Link, 1, 1, 1>(new Link), nullptr, x,
                           x + 1);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Link, 1, 1, 1>(new Link), nullptr, x,
                           x + 2);
  const ChainCovariance chain = ComputeChainCovariance(&problem, {x, x + 1, x + 2}, {});
  EXPECT_FALSE(chain.ok);
  EXPECT_NE(chain.error.find("not a chain"), std::string::npos);
}

TEST(ChainCovariance, RandomWalkVariancesByHand) {
  // x0 ~ N(0, 1), x_{k+1} - x_k ~ N(0, 1): var(x_k) = k + 1.
  ceres::Problem problem;
  double x[4] = {0.0, 0.0, 0.0, 0.0};
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Anchor, 1, 1>(new Anchor), nullptr, x);
  for (int k = 0; k < 3; ++k) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Link, 1, 1, 1>(new Link), nullptr,
                             x + k, x + k + 1);
  }
  const ChainCovariance chain = ComputeChainCovariance(&problem, {x, x + 1, x + 2, x + 3}, {});
  ASSERT_TRUE(chain.ok) << chain.error;
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(chain.states[k](0, 0), k + 1.0, 1e-12);
  // cov(x_{k+1}, x_k) = var(x_k) = k + 1 for a random walk.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(chain.next[k](0, 0), k + 1.0, 1e-12);
}

// The Gauss-Newton step of the chain: a linear chain of 2-vectors with a shared offset (the
// border) is solved in one step to Ceres' own solution, and the step's covariance is the
// covariance's.
struct OffsetMeasurement {
  double z0, z1;
  template <typename T>
  bool operator()(const T* x, const T* c, T* r) const {
    r[0] = (x[0] + c[0] - z0) / 0.5;
    r[1] = (x[1] - 2.0 * c[0] - z1) / 0.3;
    return true;
  }
};
struct PairLink {
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    r[0] = (b[0] - a[0] - 0.1) / 0.2;
    r[1] = (b[1] - a[1] + 0.05 * a[0]) / 0.4;
    return true;
  }
};
struct PairAnchor {
  template <typename T>
  bool operator()(const T* a, T* r) const {
    r[0] = a[0] / 2.0;
    r[1] = a[1] / 2.0;
    return true;
  }
};
struct OffsetPrior {
  template <typename T>
  bool operator()(const T* c, T* r) const {
    r[0] = (c[0] - 0.3) / 1.0;
    return true;
  }
};

TEST(ChainCovariance, GaussNewtonStepSolvesALinearChainWithABorder) {
  const int n = 6;
  const auto build = [&](std::vector<std::array<double, 2>>* x, double* c, ceres::Problem* p) {
    p->AddResidualBlock(new ceres::AutoDiffCostFunction<PairAnchor, 2, 2>(new PairAnchor), nullptr,
                        (*x)[0].data());
    p->AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetPrior, 1, 1>(new OffsetPrior),
                        nullptr, c);
    for (int k = 0; k < n; ++k) {
      p->AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetMeasurement, 2, 2, 1>(
                              new OffsetMeasurement{0.1 * k + 0.2, -0.3 + 0.05 * k * k}),
                          nullptr, (*x)[k].data(), c);
      if (k > 0) {
        p->AddResidualBlock(new ceres::AutoDiffCostFunction<PairLink, 2, 2, 2>(new PairLink),
                            nullptr, (*x)[k - 1].data(), (*x)[k].data());
      }
    }
  };
  std::vector<std::array<double, 2>> x(n, {1.0, -1.0}), x_ceres = x;
  double c = 0.0, c_ceres = 0.0;
  ceres::Problem problem, reference;
  build(&x, &c, &problem);
  build(&x_ceres, &c_ceres, &reference);
  ceres::Solver::Options options;
  options.function_tolerance = options.gradient_tolerance = options.parameter_tolerance = 1e-14;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &reference, &summary);

  std::vector<double*> states;
  for (auto& s : x) states.push_back(s.data());
  const ChainStep step = ComputeChainStep(&problem, states, {&c}, true);
  ASSERT_TRUE(step.ok) << step.error;
  EXPECT_GT(step.cost, summary.final_cost);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(x[k][i] + step.states[k][i], x_ceres[k][i], 1e-7);
  }
  EXPECT_NEAR(c + step.globals[0], c_ceres, 1e-7);  // Ceres stops within its tolerances
  const ChainCovariance covariance = ComputeChainCovariance(&problem, states, {&c});
  ASSERT_TRUE(step.covariance.ok);
  for (int k = 0; k < n; ++k) {
    EXPECT_LT((step.covariance.states[k] - covariance.states[k]).norm(), 1e-12);
  }
}

// The sensitivity of the solution to a model constant: on the linear chain, one measurement's
// value moved by delta changes the residuals by t at the solution, and -H^-1 J' t is exactly
// how far the solution moves (a linear problem: the re-solve agrees to Ceres' tolerance).
TEST(ChainCovariance, SensitivityIsTheSolutionsShiftWhenAConstantMoves) {
  const int n = 6;
  const auto build = [&](double shift, std::vector<std::array<double, 2>>* x, double* c,
                         ceres::Problem* p) {
    p->AddResidualBlock(new ceres::AutoDiffCostFunction<PairAnchor, 2, 2>(new PairAnchor), nullptr,
                        (*x)[0].data());
    p->AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetPrior, 1, 1>(new OffsetPrior),
                        nullptr, c);
    for (int k = 0; k < n; ++k) {
      const double z0 = 0.1 * k + 0.2 + (k == 2 ? shift : 0.0);
      p->AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetMeasurement, 2, 2, 1>(
                              new OffsetMeasurement{z0, -0.3 + 0.05 * k * k}),
                          nullptr, (*x)[k].data(), c);
      if (k > 0) {
        p->AddResidualBlock(new ceres::AutoDiffCostFunction<PairLink, 2, 2, 2>(new PairLink),
                            nullptr, (*x)[k - 1].data(), (*x)[k].data());
      }
    }
  };
  constexpr double kShift = 0.4;
  std::vector<std::array<double, 2>> x(n, {1.0, -1.0}), x_moved = x, x_eval = x;
  double c = 0.0, c_moved = 0.0, c_eval = 0.0;
  ceres::Problem problem, moved, evaluated;
  build(0.0, &x, &c, &problem);
  build(kShift, &x_moved, &c_moved, &moved);
  build(kShift, &x_eval, &c_eval, &evaluated);
  ceres::Solver::Options options;
  options.function_tolerance = options.gradient_tolerance = options.parameter_tolerance = 1e-15;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ceres::Solve(options, &moved, &summary);
  // t: the moved problem's residuals minus the original's, both at the original solution.
  x_eval = x;
  c_eval = c;
  std::vector<double> r0, r1;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, &r0, nullptr, nullptr);
  evaluated.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, &r1, nullptr, nullptr);
  ASSERT_EQ(r0.size(), r1.size());
  Eigen::VectorXd t(static_cast<Eigen::Index>(r0.size()));
  for (size_t i = 0; i < r0.size(); ++i) t[static_cast<Eigen::Index>(i)] = r1[i] - r0[i];
  std::vector<double*> states;
  for (auto& s : x) states.push_back(s.data());
  const ChainSensitivity sensitivity = ComputeChainSensitivity(&problem, states, {&c}, {t, -t});
  ASSERT_TRUE(sensitivity.ok) << sensitivity.error;
  ASSERT_EQ(sensitivity.states.size(), 2u);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(sensitivity.states[0][k][i], x_moved[k][i] - x[k][i], 1e-9) << k << " " << i;
      EXPECT_NEAR(sensitivity.states[1][k][i], -(x_moved[k][i] - x[k][i]), 1e-9);
    }
  }
  EXPECT_NEAR(sensitivity.globals[0][0], c_moved - c, 1e-9);
  // The measured state moves most; the shift is not trivially zero anywhere near it.
  EXPECT_GT(std::abs(sensitivity.states[0][2][0]), 0.05);
  // A shift of the wrong length is refused.
  EXPECT_FALSE(ComputeChainSensitivity(&problem, states, {&c}, {Eigen::VectorXd::Ones(3)}).ok);
}

}  // namespace
}  // namespace slipgraph
