#include "workbench/graph_score_test.h"

#include <ceres/cost_function.h>
#include <ceres/crs_matrix.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "factors/ward_state.h"
#include "workbench/robust_statistics.h"

namespace slipgraph {

std::array<GraphScore, kModelEffectCount> GraphScoreTests(WardProblem& problem,
                                                          const std::vector<int>& in_model) {
  std::array<GraphScore, kModelEffectCount> out{};
  ceres::Problem& p = *problem.problem;
  const size_t n = problem.states.size();
  if (n == 0 || !p.HasParameterBlock(problem.effects.data())) return out;

  // Columns: the states, the offsets, the effects (in that order).
  ceres::Problem::EvaluateOptions options;
  for (auto& x : problem.states) options.parameter_blocks.push_back(x.data());
  options.parameter_blocks.push_back(problem.offsets.data());
  options.parameter_blocks.push_back(problem.effects.data());
  const int effect_column = static_cast<int>(ward::kStateSize * n + 2);
  // Rows: every residual block, remembering its state (global priors count with the first).
  std::vector<int> row_state;
  for (const auto& [kind, ids] : problem.blocks) {
    const std::vector<long>& states = problem.block_states.at(kind);
    for (size_t b = 0; b < ids.size(); ++b) {
      options.residual_blocks.push_back(ids[b]);
      const int rows = p.GetCostFunctionForResidualBlock(ids[b])->num_residuals();
      row_state.insert(row_state.end(), rows, static_cast<int>(std::max(0L, states[b])));
    }
  }
  std::vector<double> r;
  ceres::CRSMatrix crs;
  double cost = 0.0;
  if (!p.Evaluate(options, &cost, &r, nullptr, &crs)) {
    throw std::runtime_error("graph score test: Ceres could not evaluate the problem");
  }
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  const Sparse J = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>>(
      crs.num_rows, crs.num_cols, static_cast<int>(crs.values.size()), crs.rows.data(),
      crs.cols.data(), crs.values.data());
  const Eigen::Map<const Eigen::VectorXd> residuals(r.data(), static_cast<Eigen::Index>(r.size()));

  // Nuisance columns: states, offsets and the effects in the model; the others are tested.
  std::vector<int> nuisance, tested;
  for (int c = 0; c < effect_column; ++c) nuisance.push_back(c);
  for (int e = 0; e < kModelEffectCount; ++e) {
    const bool in = std::find(in_model.begin(), in_model.end(), e) != in_model.end();
    (in ? nuisance : tested).push_back(effect_column + e);
  }
  if (tested.empty()) return out;
  const auto Select = [&](const std::vector<int>& columns) {
    Sparse s(J.cols(), static_cast<Eigen::Index>(columns.size()));
    std::vector<Eigen::Triplet<double>> ones;
    for (size_t i = 0; i < columns.size(); ++i) ones.emplace_back(columns[i], int(i), 1.0);
    s.setFromTriplets(ones.begin(), ones.end());
    return Sparse(J * s);
  };
  const Sparse N = Select(nuisance);
  const Eigen::MatrixXd T = Eigen::MatrixXd(Select(tested));

  // N'N, with a relative ridge of 1e-10 on its diagonal (and 1e-12 where a column is empty) for
  // directions no factor constrains: they carry no information about any effect either.
  Sparse A = Sparse(N.transpose() * N);
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) *= 1.0 + 1e-10;
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 1e-12;
  Eigen::SimplicialLDLT<Sparse> solver(A);
  if (solver.info() != Eigen::Success) return out;
  const Eigen::MatrixXd X = solver.solve(Eigen::MatrixXd(N.transpose() * T));
  const Eigen::VectorXd y = solver.solve(Eigen::VectorXd(N.transpose() * residuals));
  if (solver.info() != Eigen::Success) return out;
  const Eigen::MatrixXd W = T - N * X;                     // the effects' own directions
  const Eigen::VectorXd r_perp = residuals - N * y;        // r, had the solve fully converged

  for (size_t j = 0; j < tested.size(); ++j) {
    GraphScore& g = out[tested[j] - effect_column];
    const double information = W.col(j).squaredNorm();
    if (!(information > 0.0)) continue;
    const double score = W.col(j).dot(r_perp);
    // The score's contributions per state from the residuals once the one-step magnitude is
    // taken out (as a regression's HAC uses its fitted residuals): under the alternative the raw
    // residuals still hold the effect, which would inflate the variance and hide it.
    const double theta = -score / information;
    std::vector<double> contribution(n, 0.0);
    for (Eigen::Index i = 0; i < W.rows(); ++i) {
      contribution[row_state[i]] += W(i, j) * (r_perp[i] + W(i, j) * theta);
    }
    const double robust_variance = BartlettLongRunVariance(contribution, &g.lag);
    g.tested = true;
    g.magnitude = theta;
    g.model_sd = 1.0 / std::sqrt(information);
    g.robust_sd = std::sqrt(robust_variance) / information;
    g.states = n;
  }
  return out;
}

}  // namespace slipgraph
