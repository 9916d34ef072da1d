// ChainCovariance against ceres::Covariance on the Ward problem of a short simulated log, and
// its refusal of a problem that is not a chain.
#include "solvers/chain_covariance.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/covariance.h>
#include <ceres/crs_matrix.h>
#include <ceres/loss_function.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "factors/ward_state.h"
#include "problems/ward_batch_problem.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ekf_runner.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace {

// The Ward batch problem on fig5 (seed 1), from the EKF's estimates, and its states' blocks.
struct Fig5Problem {
  std::unique_ptr<WardProblem> problem;
  std::vector<double*> states;
};
Fig5Problem MakeFig5Problem() {
  const sim::ScenarioRun run = sim::ExpandScenario("fig5", 1).at(0);
  const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  Fig5Problem out{BuildWardBatchProblem(log, model, RunEkf(log, model).estimates), {}};
  for (auto& x : out.problem->states) out.states.push_back(x.data());
  return out;
}

TEST(ChainCovariance, MatchesCeresCovarianceOnAWardProblem) {
  DriveLog log = testing::SimulatedScenario("fig5");
  testing::CutLog(&log, 2.0, 6.0);  // around the start of motion: 400 states, for SPARSE_QR
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

// The linearization's cost and gradient are Problem::Evaluate's: the residual blocks evaluated
// without Ceres, their robust losses (Huber, Cauchy) corrected as Ceres' solver corrects them,
// on one thread and on two (each over its own run of states, the blocks between them after).
TEST(ChainCovariance, LinearizationIsCeresEvaluationOnOneThreadOrTwo) {
  const Fig5Problem fig5 = MakeFig5Problem();
  WardProblem* problem = fig5.problem.get();
  const std::vector<double*>& states = fig5.states;
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = states;
  options.parameter_blocks.push_back(problem->offsets.data());
  double cost = 0.0;
  std::vector<double> gradient;
  ASSERT_TRUE(problem->problem->Evaluate(options, &cost, nullptr, &gradient, nullptr));
  double largest = 0.0;
  for (const double g : gradient) largest = std::max(largest, std::abs(g));
  int robust = 0;  // residual blocks with a loss
  std::vector<ceres::ResidualBlockId> ids;
  problem->problem->GetResidualBlocks(&ids);
  for (const ceres::ResidualBlockId id : ids) {
    if (problem->problem->GetLossFunctionForResidualBlock(id) != nullptr) ++robust;
  }
  ASSERT_GT(robust, 1000);
  for (const int threads : {1, 2}) {
    ChainLinearization linearization;
    std::string error;
    ASSERT_TRUE(linearization.Linearize(problem->problem.get(), states, {problem->offsets.data()},
                                        &error, threads))
        << error;
    EXPECT_NEAR(linearization.cost(), cost, 1e-12 * cost) << threads;
    ASSERT_EQ(linearization.gradient().size(), gradient.size());
    for (size_t i = 0; i < gradient.size(); ++i) {
      ASSERT_NEAR(linearization.gradient()[i], gradient[i], 1e-9 * largest) << threads << " " << i;
    }
  }
}

TEST(ChainCovariance, TheLinearizationsCostIsCeresCostWhereverTheStatesMove) {
  const Fig5Problem fig5 = MakeFig5Problem();
  WardProblem* problem = fig5.problem.get();
  const std::vector<double*>& states = fig5.states;
  ChainLinearization linearization;
  double unread = 0.0;
  EXPECT_FALSE(linearization.Cost(&unread));  // no blocks read yet
  std::string error;
  ASSERT_TRUE(
      linearization.Linearize(problem->problem.get(), states, {problem->offsets.data()}, &error))
      << error;
  // Where it linearized: the linearization's own cost, summed in the same order.
  for (const int threads : {1, 2}) {
    double here = 0.0;
    ASSERT_TRUE(linearization.Cost(&here, threads));
    EXPECT_EQ(here, linearization.cost()) << threads;
  }
  // Moved after the blocks were read, as a trial step moves them.
  for (size_t k = 0; k < states.size(); ++k) states[k][ward::kVbx] += 0.01 * std::sin(0.1 * k);
  problem->offsets[0] += 0.003;
  double ceres_cost = 0.0;
  ASSERT_TRUE(problem->problem->Evaluate({}, &ceres_cost, nullptr, nullptr, nullptr));
  ASSERT_GT(std::abs(ceres_cost - linearization.cost()), 1e-3 * ceres_cost);  // it did move
  for (const int threads : {1, 2}) {
    double cost = 0.0;
    ASSERT_TRUE(linearization.Cost(&cost, threads));
    // Ceres sums the same blocks' costs in another order: rounding over some 10^5 terms.
    EXPECT_NEAR(cost, ceres_cost, 1e-12 * ceres_cost) << threads;
  }
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
  ChainLinearization linearization;
  EXPECT_FALSE(linearization.LastStepCovariance().ok);  // nothing factored yet
  std::string error;
  ASSERT_TRUE(linearization.Linearize(&problem, states, {&c}, &error)) << error;
  EXPECT_FALSE(linearization.LastStepCovariance().ok);  // linearized, not yet stepped
  ChainStep step;
  ASSERT_TRUE(linearization.Step(0.0, &step)) << step.error;
  EXPECT_GT(step.cost, summary.final_cost);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(x[k][i] + step.states[k][i], x_ceres[k][i], 1e-7);
  }
  EXPECT_NEAR(c + step.globals[0], c_ceres, 1e-7);  // Ceres stops within its tolerances
  const ChainCovariance covariance = ComputeChainCovariance(&problem, states, {&c});
  const ChainCovariance from_step = linearization.LastStepCovariance();
  ASSERT_TRUE(from_step.ok);
  for (int k = 0; k < n; ++k) {
    EXPECT_LT((from_step.states[k] - covariance.states[k]).norm(), 1e-12);
  }
  EXPECT_LT((from_step.globals - covariance.globals).norm(), 1e-12);
  // The first two states' only (as the window asks for the states that leave it).
  const ChainCovariance first_two = linearization.LastStepCovariance(2);
  ASSERT_TRUE(first_two.ok);
  ASSERT_EQ(first_two.states.size(), static_cast<size_t>(n));
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT((first_two.states[k] - covariance.states[k]).norm(), 1e-12);
  }
  EXPECT_EQ(first_two.states[2].size(), 0);  // not asked for
  EXPECT_TRUE(first_two.next.empty());
  // A linearization that fails leaves nothing of the last one to read.
  EXPECT_FALSE(linearization.Linearize(&problem, {}, {&c}, &error));
  EXPECT_FALSE(linearization.LastStepCovariance().ok);
  double cost = 0.0;
  EXPECT_FALSE(linearization.Cost(&cost));
}

// Ceres' loss correction where the loss curves up (rho'' > 0: TolerantLoss), the one case that
// changes the Jacobian's direction as well as its scale: the Gauss-Newton step from the
// linearization is the one from Problem::Evaluate's loss-corrected Jacobian.
struct Bend {
  double z;
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    r[0] = a[0] * b[0] - z;
    r[1] = a[0] - 2.0 * b[0] + z;
    return true;
  }
};

TEST(ChainCovariance, LossCorrectionIsCeresWhereTheLossCurvesUp) {
  std::array<double, 3> x = {0.7, -0.4, 1.3};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Anchor, 1, 1>(new Anchor), nullptr,
                           &x[0]);
  for (int k = 0; k < 2; ++k) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Bend, 2, 1, 1>(new Bend{0.5 + k}),
                             new ceres::TolerantLoss(0.5, 0.3), &x[k], &x[k + 1]);
  }
  std::vector<double*> states = {&x[0], &x[1], &x[2]};
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = states;
  double cost = 0.0;
  std::vector<double> residuals;
  ceres::CRSMatrix crs;
  ASSERT_TRUE(problem.Evaluate(options, &cost, &residuals, nullptr, &crs));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int e = crs.rows[row]; e < crs.rows[row + 1]; ++e) J(row, crs.cols[e]) = crs.values[e];
  }
  const Eigen::VectorXd r = Eigen::Map<Eigen::VectorXd>(residuals.data(), residuals.size());
  const Eigen::VectorXd expected = -(J.transpose() * J).ldlt().solve(J.transpose() * r);
  ChainLinearization linearization;
  std::string error;
  ASSERT_TRUE(linearization.Linearize(&problem, states, {}, &error)) << error;
  EXPECT_NEAR(linearization.cost(), cost, 1e-14);
  ChainStep step;
  ASSERT_TRUE(linearization.Step(0.0, &step)) << step.error;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(step.states[k][0], expected[k], 1e-10) << k;
}

// The linearization's model of the cost: on a linear chain with a border the cost is exactly
// quadratic, so the predicted decrease of any step (here the damped ones too) is the decrease
// the step makes, which checks J'r and every block of H (diagonal, off-diagonal, border).
TEST(ChainCovariance, PredictedDecreaseIsTheDecreaseOnALinearChain) {
  const int n = 5;
  std::vector<std::array<double, 2>> x(n, {1.0, -1.0});
  double c = 0.0;
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PairAnchor, 2, 2>(new PairAnchor),
                           nullptr, x[0].data());
  for (int k = 0; k < n; ++k) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetMeasurement, 2, 2, 1>(
                                 new OffsetMeasurement{0.3 * k, 0.1 * k * k}),
                             nullptr, x[k].data(), &c);
    if (k > 0) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PairLink, 2, 2, 2>(new PairLink),
                               nullptr, x[k - 1].data(), x[k].data());
    }
  }
  std::vector<double*> states;
  for (auto& s : x) states.push_back(s.data());
  ChainLinearization linearization;
  std::string error;
  ASSERT_TRUE(linearization.Linearize(&problem, states, {&c}, &error)) << error;
  for (const double mu : {0.0, 0.1, 10.0}) {
    ChainStep step;
    ASSERT_TRUE(linearization.Step(mu, &step)) << step.error;
    const std::vector<std::array<double, 2>> x0 = x;
    const double c0 = c;
    for (int k = 0; k < n; ++k) {
      for (int i = 0; i < 2; ++i) x[k][i] += step.states[k][i];
    }
    c += step.globals[0];
    double cost = 0.0;
    ASSERT_TRUE(linearization.Cost(&cost));
    EXPECT_NEAR(linearization.PredictedDecrease(step.states, step.globals),
                linearization.cost() - cost, 1e-9 * linearization.cost())
        << "mu " << mu;
    EXPECT_LT(linearization.Slope(step.states, step.globals), 0.0);
    x = x0;
    c = c0;
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
  ResidualShifts shifts;
  problem.GetResidualBlocks(&shifts.blocks);
  shifts.columns = {t, -t};
  const ChainSensitivity sensitivity = ComputeChainSensitivity(&problem, states, {&c}, shifts);
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
  // Given on the measured block alone (the only one the move shifts): the same.
  ResidualShifts measured;
  Eigen::Index row = 0;
  for (const ceres::ResidualBlockId id : shifts.blocks) {
    const int rows = problem.GetCostFunctionForResidualBlock(id)->num_residuals();
    if (t.segment(row, rows).cwiseAbs().maxCoeff() > 0.0) {
      measured.blocks.push_back(id);
      measured.columns.push_back(t.segment(row, rows));
    }
    row += rows;
  }
  ASSERT_EQ(measured.blocks.size(), 1u);
  const ChainSensitivity alone = ComputeChainSensitivity(&problem, states, {&c}, measured);
  ASSERT_TRUE(alone.ok) << alone.error;
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(alone.states[0][k][0], sensitivity.states[0][k][0], 1e-12) << k;
  }
  // A shift of the wrong length is refused.
  measured.columns = {Eigen::VectorXd::Ones(3)};
  EXPECT_FALSE(ComputeChainSensitivity(&problem, states, {&c}, measured).ok);
}

// Chains whose border is mostly local, as the tire law's stiffness nodes are: node j is read by
// the states of [8 j - 2, 8 j + 8) only (the first two with node j - 1 too), consecutive nodes are
// tied by a walk and nodes 3 and 5, which no state reads together, by another; a two-column node
// is read by states 40-49. With a tail, an offset is read throughout and the last node by the
// last state; without, the last states read no global. Every result of the linearization is
// checked against the dense H = J'J of Problem::Evaluate's Jacobian, the globals given in a
// scrambled order. The tolerances are a few hundred times the rounding of H's entries.
struct NodeMeasurement {  // x_k against node j
  double z, a;
  template <typename T>
  bool operator()(const T* x, const T* node, T* r) const {
    r[0] = (x[0] - a * node[0] - z) / 0.3;
    return true;
  }
};
struct NodeDrift {  // x_k to x_{k+1}, driven by node j
  template <typename T>
  bool operator()(const T* a, const T* b, const T* node, T* r) const {
    r[0] = (b[0] - a[0] - 0.05 * node[0] - 0.01) / 0.2;
    r[1] = (b[1] - a[1] + 0.05 * a[0]) / 0.4;
    return true;
  }
};
struct NodeBlend {  // x_k against two nodes
  double w;
  template <typename T>
  bool operator()(const T* x, const T* n0, const T* n1, T* r) const {
    r[0] = (x[1] - w * n0[0] - (1.0 - w) * n1[0]) / 0.5;
    return true;
  }
};
struct NodeWalk {
  template <typename T>
  bool operator()(const T* n0, const T* n1, T* r) const {
    r[0] = (n1[0] - n0[0]) / 0.7;
    return true;
  }
};
struct PairNodeMeasurement {  // x_k against a two-column node
  template <typename T>
  bool operator()(const T* x, const T* node, T* r) const {
    r[0] = (x[0] - node[0] + 0.3 * node[1]) / 0.4;
    r[1] = (x[1] - node[1]) / 0.6;
    return true;
  }
};

struct LocalBorderChain {
  static constexpr int kNodes = 16, n = 8 * kNodes + 4;
  std::vector<std::array<double, 2>> x = std::vector<std::array<double, 2>>(n);
  std::array<double, kNodes> nodes{};
  std::array<double, 2> pair = {0.3, -0.2};
  double c = 0.2;
  ceres::Problem problem;
  std::vector<double*> states, globals;

  explicit LocalBorderChain(bool with_tail) {
    for (int k = 0; k < n; ++k) x[k] = {0.1 * k, std::sin(0.3 * k)};
    for (int j = 0; j < kNodes; ++j) nodes[j] = 0.3 * std::cos(1.3 * j);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PairAnchor, 2, 2>(new PairAnchor),
                             nullptr, x[0].data());
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetPrior, 1, 1>(new OffsetPrior),
                             nullptr, &nodes[0]);
    for (int j = 0; j + 1 < kNodes; ++j) Walk(j, j + 1);
    Walk(3, 5);
    // With a tail the last node is read to the last state; without, every global closes early.
    const int reading = with_tail ? n : n - 3;
    for (int k = 0; k < n; ++k) {
      const int j = std::min(kNodes - 1, k / 8);
      if (with_tail) {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetMeasurement, 2, 2, 1>(
                                     new OffsetMeasurement{0.1 * k, 0.02 * k * k}),
                                 nullptr, x[k].data(), &c);
      }
      if (k < reading) {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<NodeMeasurement, 1, 2, 1>(
                                     new NodeMeasurement{0.05 * k, 1.0 + 0.1 * (k % 3)}),
                                 nullptr, x[k].data(), &nodes[j]);
      }
      if (k < reading && k % 8 >= 6 && j + 1 < kNodes) {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<NodeBlend, 1, 2, 1, 1>(
                                     new NodeBlend{0.25 * (k % 8 - 5)}),
                                 nullptr, x[k].data(), &nodes[j], &nodes[j + 1]);
      }
      if (k >= 40 && k < 50) {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<PairNodeMeasurement, 2, 2, 2>(new PairNodeMeasurement),
            nullptr, x[k].data(), pair.data());
      }
      if (k + 1 < n && k + 1 < reading) {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<NodeDrift, 2, 2, 2, 1>(new NodeDrift), nullptr,
            x[k].data(), x[k + 1].data(), &nodes[j]);
      } else if (k + 1 < n) {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PairLink, 2, 2, 2>(new PairLink),
                                 nullptr, x[k].data(), x[k + 1].data());
      }
    }
    for (auto& s : x) states.push_back(s.data());
    for (int j = kNodes - 1; j >= 0; j -= 2) globals.push_back(&nodes[j]);
    globals.push_back(pair.data());
    if (with_tail) globals.push_back(&c);
    for (int j = kNodes - 2; j >= 0; j -= 2) globals.push_back(&nodes[j]);
  }
  void Walk(int a, int b) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<NodeWalk, 1, 1, 1>(new NodeWalk),
                             nullptr, &nodes[a], &nodes[b]);
  }
};

void ExpectTheDenseSolution(LocalBorderChain* chain, int local_columns) {
  ceres::Problem& problem = chain->problem;
  const std::vector<double*>& states = chain->states;
  const std::vector<double*>& globals = chain->globals;
  const int n = LocalBorderChain::n, g = LocalBorderChain::kNodes + 2 + (local_columns < 18),
            size = 2 * n + g;
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = states;
  options.parameter_blocks.insert(options.parameter_blocks.end(), globals.begin(), globals.end());
  double cost = 0.0;
  std::vector<double> residuals, gradient;
  ceres::CRSMatrix crs;
  ASSERT_TRUE(problem.Evaluate(options, &cost, &residuals, &gradient, &crs));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int e = crs.rows[row]; e < crs.rows[row + 1]; ++e) J(row, crs.cols[e]) = crs.values[e];
  }
  ASSERT_EQ(J.cols(), size);
  const Eigen::MatrixXd H = J.transpose() * J;
  const Eigen::VectorXd grad = Eigen::Map<Eigen::VectorXd>(gradient.data(), size);
  const auto stacked = [&](const ChainStep& step) {
    Eigen::VectorXd d(size);
    for (int k = 0; k < n; ++k) d.segment(2 * k, 2) = step.states[k];
    d.tail(g) = step.globals;
    return d;
  };

  ChainLinearization linearization;
  std::string error;
  ASSERT_TRUE(linearization.Linearize(&problem, states, globals, &error)) << error;
  EXPECT_EQ(linearization.LocalBorderColumns(), local_columns);
  EXPECT_NEAR(linearization.cost(), cost, 1e-12 * cost);
  for (int i = 0; i < size; ++i) ASSERT_NEAR(linearization.gradient()[i], grad[i], 1e-10) << i;

  // Gauss-Newton and damped steps.
  for (const double mu : {0.0, 0.3}) {
    Eigen::MatrixXd damped = H;
    for (int i = 0; i < size; ++i) damped(i, i) += mu * std::clamp(H(i, i), 1e-6, 1e32);
    const Eigen::VectorXd expected = damped.ldlt().solve(-grad);
    ChainStep step;
    ASSERT_TRUE(linearization.Step(mu, &step)) << step.error;
    const Eigen::VectorXd d = stacked(step);
    EXPECT_LT((d - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff()) << mu;
    EXPECT_NEAR(linearization.PredictedDecrease(step.states, step.globals),
                -(grad.dot(d) + 0.5 * d.dot(H * d)), 1e-10 * cost)
        << mu;
  }
  // Held columns (a state's component, a node, the two-column node's second): cut from H, their
  // step 0.
  std::vector<char> held(size, 0);
  const int pair_column = 2 * n + LocalBorderChain::kNodes / 2 + 1;  // globals' order
  held[2 * 13 + 1] = held[2 * n + 4] = held[pair_column] = 1;
  {
    Eigen::MatrixXd cut = H;
    Eigen::VectorXd rhs = -grad;
    for (int i = 0; i < size; ++i) {
      if (held[i] == 0) continue;
      cut.row(i).setZero();
      cut.col(i).setZero();
      cut(i, i) = 1.0;
      rhs[i] = 0.0;
    }
    const Eigen::VectorXd expected = cut.ldlt().solve(rhs);
    ChainStep step;
    ASSERT_TRUE(linearization.Step(0.0, &step, &held)) << step.error;
    const Eigen::VectorXd d = stacked(step);
    EXPECT_LT((d - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
    EXPECT_EQ(d[2 * n + 4], 0.0);
    EXPECT_EQ(d[pair_column], 0.0);
  }
  // The marginal covariances: every state, consecutive pairs, the globals that share a front.
  ChainStep step;
  ASSERT_TRUE(linearization.Step(0.0, &step)) << step.error;
  const ChainCovariance covariance = linearization.LastStepCovariance();
  ASSERT_TRUE(covariance.ok) << covariance.error;
  const Eigen::MatrixXd inverse = H.inverse();
  for (int k = 0; k < n; ++k) {
    EXPECT_LT((covariance.states[k] - inverse.block(2 * k, 2 * k, 2, 2)).norm(), 1e-10) << k;
    if (k + 1 < n) {
      EXPECT_LT((covariance.next[k] - inverse.block(2 * k + 2, 2 * k, 2, 2)).norm(), 1e-10) << k;
    }
  }
  int compared = 0;
  for (int i = 0; i < g; ++i) {
    EXPECT_FALSE(std::isnan(covariance.globals(i, i))) << i;
    for (int j = 0; j < g; ++j) {
      if (std::isnan(covariance.globals(i, j))) continue;
      EXPECT_NEAR(covariance.globals(i, j), inverse(2 * n + i, 2 * n + j), 1e-10) << i << " " << j;
      ++compared;
    }
  }
  EXPECT_GE(compared, 3 * g - 2);  // the diagonal and each node with its neighbours at least
  // The first states' only, as the window asks for the states that leave it.
  const ChainCovariance first = linearization.LastStepCovariance(5);
  ASSERT_TRUE(first.ok) << first.error;
  EXPECT_LT((first.states[4] - covariance.states[4]).norm(), 1e-14);
  EXPECT_EQ(first.states[5].size(), 0);
  const ChainCovariance recomputed = ComputeChainCovariance(&problem, states, globals);
  ASSERT_TRUE(recomputed.ok) << recomputed.error;
  EXPECT_LT((recomputed.states[20] - covariance.states[20]).norm(), 1e-14);

  // The sensitivity to a shift of every residual: -H^-1 J' t.
  ResidualShifts shifts;
  problem.GetResidualBlocks(&shifts.blocks);
  Eigen::VectorXd t(crs.num_rows);
  for (int i = 0; i < crs.num_rows; ++i) t[i] = std::cos(1.7 * i);
  shifts.columns = {t};
  const ChainSensitivity sensitivity = ComputeChainSensitivity(&problem, states, globals, shifts);
  ASSERT_TRUE(sensitivity.ok) << sensitivity.error;
  const Eigen::VectorXd expected = -H.ldlt().solve(J.transpose() * t);
  for (int k = 0; k < n; ++k) {
    EXPECT_LT((sensitivity.states[0][k] - expected.segment(2 * k, 2)).norm(), 1e-10) << k;
  }
  EXPECT_LT((sensitivity.globals[0] - expected.tail(g)).norm(), 1e-10);
}

TEST(ChainCovariance, ALocalBorderWithATailIsSolvedAsTheDenseSystem) {
  LocalBorderChain chain(true);
  // The nodes but the last (15) and the two-column node's two; the offset and the last node: the
  // tail.
  ExpectTheDenseSolution(&chain, 17);
}

TEST(ChainCovariance, ABorderThatIsAllLocalIsSolvedAsTheDenseSystem) {
  LocalBorderChain chain(false);
  ExpectTheDenseSolution(&chain, 18);
}

}  // namespace
}  // namespace slipgraph
