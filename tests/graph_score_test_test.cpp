// The graph score test against an independent computation: its one-step magnitude must be the
// effect's component of a full Gauss-Newton step with every effect column free (block
// elimination), and its model sd the square root of that component's variance in (J'J)^-1,
// computed densely on a short log (agreement to 1e-3 of the sd: the system is ill-conditioned, the
// factors' sigmas span 1e-4 to 1e2).
#include "workbench/graph_score_test.h"

#include <ceres/cost_function.h>
#include <ceres/crs_matrix.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <stdexcept>
#include <utility>
#include <vector>

#include "factors/catalogue_terms.h"
#include "factors/ward_state.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/batch_smoother.h"

namespace slipgraph {
namespace {

// 2.5 s of driving in a turn with quadratic drag, at the EKF's estimates (not an optimum: the
// test also covers the residual's projection).
struct ShortLog {
  DriveLog log;
  ModelConfig model;
  FilterResult ekf;
};

ShortLog MakeShortLog() {
  sim::Scenario sc = sim::ExpandScenario("hidden/quadratic_drag", 1).at(0).scenario;
  sc.rest_start_s = 0.3;
  sc.commands = {{2.2, 1.0, 0.3}};
  ShortLog s{sim::Simulate(sc, 3).log, {}, {}};
  s.model = DefaultModelConfig(s.log.vehicle);
  s.ekf = RunEkf(s.log, s.model, {});
  return s;
}

ModelConfig WithAllEffects(ModelConfig model) {
  model.effects.clear();
  for (const EffectTerm& term : CatalogueTerms().all()) model.effects.push_back(term.name);
  return model;
}

// Indices in the catalogue's order (the problem's effect block).
constexpr int kQuadraticDrag = 0, kTurnSlip = 1;
const int kEffectCount = static_cast<int>(CatalogueTerms().size());

// With a tire law that varies along the path (the slip-stiffness walk's nodes, nuisance like the
// states) as without.
TEST(GraphScoreTest, MatchesTheFullGaussNewtonStep) {
  const ShortLog s = MakeShortLog();
  const ModelConfig all = WithAllEffects(s.model);
  WardProblemOptions walk;
  walk.stiffness_prior_sd = 0.3;
  walk.stiffness_node_s = 0.5;
  walk.stiffness_walk_sd = 0.3;
  walk.stiffness_with_effects = true;
  const std::vector<std::pair<WardProblemOptions, std::vector<int>>> cases = {
      {WardProblemOptions{}, {}}, {WardProblemOptions{}, {kTurnSlip}}, {walk, {kTurnSlip}}};
  for (const auto& [problem_options, in_model] : cases) {
    std::unique_ptr<WardProblem> problem =
        BuildWardBatchProblem(s.log, all, s.ekf.estimates, problem_options);
    const int nodes = static_cast<int>(problem->stiffness.size());
    ASSERT_EQ(nodes > 0, problem_options.stiffness_prior_sd > 0.0);
    // At nodes away from zero: the law's scale enters the columns.
    for (int j = 0; j < nodes; ++j) problem->stiffness[j] = 0.1 * (j % 3) - 0.1;
    const auto scores = GraphScoreTests(*problem, in_model);

    // Dense J and r over the same columns (states, offsets, effects, stiffness nodes).
    ceres::Problem::EvaluateOptions options;
    for (auto& x : problem->states) options.parameter_blocks.push_back(x.data());
    options.parameter_blocks.push_back(problem->offsets.data());
    options.parameter_blocks.push_back(problem->effects.data());
    for (double& node : problem->stiffness) options.parameter_blocks.push_back(&node);
    std::vector<bool> prior_row;
    for (const auto& [kind, ids] : problem->blocks) {
      for (ceres::ResidualBlockId id : ids) {
        options.residual_blocks.push_back(id);
        const int rows = problem->problem->GetCostFunctionForResidualBlock(id)->num_residuals();
        prior_row.insert(prior_row.end(), rows, kind == "effect_prior");
      }
    }
    std::vector<double> r;
    ceres::CRSMatrix crs;
    ASSERT_TRUE(problem->problem->Evaluate(options, nullptr, &r, nullptr, &crs));
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
    for (int i = 0; i < crs.num_rows; ++i) {
      for (int p = crs.rows[i]; p < crs.rows[i + 1]; ++p) J(i, crs.cols[p]) = crs.values[p];
    }
    const Eigen::VectorXd residuals = Eigen::Map<Eigen::VectorXd>(r.data(), r.size());
    const int first_effect = crs.num_cols - kEffectCount - nodes;

    for (int e = 0; e < kEffectCount; ++e) {
      const bool in = std::find(in_model.begin(), in_model.end(), e) != in_model.end();
      if (in) {
        EXPECT_FALSE(scores[e].tested);
        continue;
      }
      // Free: every column but the other tested effects (held at 0, as the test holds them); the
      // effects' weak prior is not data, as in the test.
      Eigen::MatrixXd Je = J;
      for (size_t i = 0; i < prior_row.size(); ++i) {
        if (prior_row[i]) Je(i, first_effect + e) = 0.0;
      }
      if (Je.col(first_effect + e).squaredNorm() == 0.0) {
        // Sinkage without effect windows acts nowhere: nothing to test.
        EXPECT_FALSE(scores[e].tested) << e;
        continue;
      }
      ASSERT_TRUE(scores[e].tested) << e;
      std::vector<int> free;
      for (int c = 0; c < first_effect; ++c) free.push_back(c);
      for (int f = 0; f < kEffectCount; ++f) {
        const bool f_in = std::find(in_model.begin(), in_model.end(), f) != in_model.end();
        if (f == e || f_in) free.push_back(first_effect + f);
      }
      for (int j = 0; j < nodes; ++j) free.push_back(first_effect + kEffectCount + j);
      Eigen::MatrixXd Jf(J.rows(), free.size());
      for (size_t c = 0; c < free.size(); ++c) Jf.col(c) = Je.col(free[c]);
      // The same ridge as the test's on the nuisance part: none on the effect's own column.
      Eigen::MatrixXd H = Jf.transpose() * Jf;
      for (size_t c = 0; c < free.size(); ++c) {
        if (free[c] != first_effect + e) H(c, c) = H(c, c) * (1.0 + 1e-10) + 1e-12;
      }
      const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
      const Eigen::VectorXd step = ldlt.solve(-Jf.transpose() * residuals);
      const size_t at = std::find(free.begin(), free.end(), first_effect + e) - free.begin();
      Eigen::VectorXd unit = Eigen::VectorXd::Zero(free.size());
      unit[at] = 1.0;
      const double variance = ldlt.solve(unit)[at];

      EXPECT_NEAR(scores[e].magnitude, step[at], 1e-3 * std::sqrt(variance)) << e;
      EXPECT_NEAR(scores[e].model_sd, std::sqrt(variance), 1e-3 * std::sqrt(variance)) << e;
      EXPECT_GT(scores[e].robust_sd, 0.0) << e;
    }
  }
}

// Drag is an external force -v |v| / m: tested as a force shape it must score as its own
// column does, and a basis that splits it in two must add up to it.
TEST(GraphScoreTest, AForceShapeScoresLikeTheEffectItIs) {
  const ShortLog s = MakeShortLog();
  std::unique_ptr<WardProblem> problem =
      BuildWardBatchProblem(s.log, WithAllEffects(s.model), s.ekf.estimates);
  const GraphProjector graph(*problem, {});
  ASSERT_TRUE(graph.ok());
  const double mass = s.log.vehicle.mass_kg;
  std::vector<double> drag(problem->states.size()), first(drag.size(), 0.0), second(first);
  for (size_t k = 0; k < drag.size(); ++k) {
    const double v = problem->states[k][ward::kVbx];
    drag[k] = -v * std::abs(v) / mass;
    (k < drag.size() / 2 ? first : second)[k] = drag[k];
  }
  const GraphScore effect = graph.EffectScores()[kQuadraticDrag];
  const GraphScore force = graph.TestForce(drag);
  ASSERT_TRUE(force.tested);
  EXPECT_NEAR(force.magnitude, effect.magnitude, 1e-6 * effect.model_sd);
  EXPECT_NEAR(force.model_sd, effect.model_sd, 1e-9 * effect.model_sd);
  EXPECT_NEAR(force.robust_sd, effect.robust_sd, 1e-6 * effect.robust_sd);

  const ProjectedBasis basis = graph.ProjectForces({first, second});
  const double score = basis.score.sum(), information = basis.gram.sum();
  EXPECT_NEAR(-score / information, effect.magnitude, 1e-6 * effect.model_sd);
  EXPECT_NEAR(1.0 / std::sqrt(information), effect.model_sd, 1e-9 * effect.model_sd);

  // The effect's own column appended to the basis: its entries are its single test's, and it
  // is the basis's sum (cross terms and all). The graph spans several of the projection's bands
  // of rows.
  ASSERT_GT(graph.rows(), 2 * 2048);
  const Eigen::VectorXd column = graph.EffectColumn(kQuadraticDrag);
  const ProjectedBasis joint = graph.ProjectForces({first, second}, &column);
  ASSERT_EQ(joint.score.size(), 3);
  EXPECT_NEAR(1.0 / std::sqrt(joint.gram(2, 2)), effect.model_sd, 1e-9 * effect.model_sd);
  EXPECT_NEAR(-joint.score[2] / joint.gram(2, 2), effect.magnitude, 1e-6 * effect.model_sd);
  EXPECT_NEAR(joint.gram(2, 0) + joint.gram(2, 1), joint.gram(2, 2), 1e-9 * joint.gram(2, 2));
  EXPECT_EQ(joint.gram(0, 2), joint.gram(2, 0));  // symmetric
  const Eigen::VectorXd short_column = column.head(column.size() - 1);
  EXPECT_THROW(graph.ProjectForces({first}, &short_column), std::invalid_argument);
}

TEST(GraphScoreTest, NothingToTestWithEveryEffectInTheModel) {
  const ShortLog s = MakeShortLog();
  std::unique_ptr<WardProblem> problem =
      BuildWardBatchProblem(s.log, WithAllEffects(s.model), s.ekf.estimates);
  std::vector<int> all;
  for (int e = 0; e < kEffectCount; ++e) all.push_back(e);
  const auto scores = GraphScoreTests(*problem, all);
  for (const GraphScore& g : scores) EXPECT_FALSE(g.tested);
}

}  // namespace
}  // namespace slipgraph
