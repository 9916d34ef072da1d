#include "workbench/graph_score_test.h"

#include <ceres/cost_function.h>
#include <ceres/crs_matrix.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "factors/ward_state.h"
#include "workbench/robust_statistics.h"

namespace slipgraph {

GraphProjector::GraphProjector(WardProblem& problem, const std::vector<int>& in_model)
    : in_model_(in_model) {
  ceres::Problem& p = *problem.problem;
  states_ = problem.states.size();
  effect_count_ = problem.effects.size();
  if (states_ == 0 || effect_count_ == 0) return;

  // Columns: the states, the offsets, the effect terms, the law's stiffness nodes (in that
  // order).
  ceres::Problem::EvaluateOptions options;
  for (auto& x : problem.states) options.parameter_blocks.push_back(x.data());
  options.parameter_blocks.push_back(problem.offsets.data());
  options.parameter_blocks.push_back(problem.effects.data());
  for (double& node : problem.stiffness) options.parameter_blocks.push_back(&node);
  effect_column_ = static_cast<int>(ward::kStateSize * states_ + 2);
  const int stiffness_column = effect_column_ + static_cast<int>(effect_count_);
  // Rows: every residual block, remembering its state (global priors count with the first) and
  // whether a force term enters it.
  for (const auto& [kind, ids] : problem.blocks) {
    const std::vector<long>& states = problem.block_states.at(kind);
    const bool model = kind == "accelerometer" || kind == "dynamics";
    const bool prior = kind == "effect_prior";
    for (size_t b = 0; b < ids.size(); ++b) {
      options.residual_blocks.push_back(ids[b]);
      const int rows = p.GetCostFunctionForResidualBlock(ids[b])->num_residuals();
      row_state_.insert(row_state_.end(), rows, static_cast<int>(std::max(0L, states[b])));
      row_is_model_.insert(row_is_model_.end(), rows, model);
      row_is_prior_.insert(row_is_prior_.end(), rows, prior);
    }
  }
  std::vector<double> r;
  ceres::CRSMatrix crs;
  double cost = 0.0;
  if (!p.Evaluate(options, &cost, &r, nullptr, &crs)) {
    throw std::runtime_error("graph score test: Ceres could not evaluate the problem");
  }
  J_ = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>>(
      crs.num_rows, crs.num_cols, static_cast<int>(crs.values.size()), crs.rows.data(),
      crs.cols.data(), crs.values.data());
  const Eigen::Map<const Eigen::VectorXd> residuals(r.data(), static_cast<Eigen::Index>(r.size()));

  // Nuisance columns: states, offsets, the effects in the model and the stiffness nodes (a law
  // that varies along the path is part of the null model).
  std::vector<Eigen::Triplet<double>> select;
  int c = 0;
  for (; c < effect_column_; ++c) select.emplace_back(c, c, 1.0);
  for (int e : in_model) select.emplace_back(effect_column_ + e, c++, 1.0);
  for (size_t j = 0; j < problem.stiffness.size(); ++j) {
    select.emplace_back(stiffness_column + static_cast<int>(j), c++, 1.0);
  }
  Sparse S(J_.cols(), c);
  S.setFromTriplets(select.begin(), select.end());
  N_ = J_ * S;
  N_rows_ = N_;

  // N'N, with a relative ridge of 1e-10 on its diagonal (and 1e-12 where a column is empty) for
  // directions no factor constrains: they carry no information about any term either.
  Sparse A = Sparse(N_.transpose() * N_);
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    A.coeffRef(i, i) = A.coeff(i, i) * (1.0 + 1e-10) + 1e-12;
  solver_.compute(A);
  if (solver_.info() != Eigen::Success) return;
  const Eigen::VectorXd y = solver_.solve(Eigen::VectorXd(N_.transpose() * residuals));
  if (solver_.info() != Eigen::Success) return;
  r_perp_ = residuals - N_ * y;  // r, had the solve fully converged
  ok_ = true;
}

Eigen::MatrixXd GraphProjector::ProjectOut(const Eigen::MatrixXd& T) const {
  return T - N_ * solver_.solve(Eigen::MatrixXd(N_.transpose() * T));
}

GraphScore GraphProjector::Test(const Eigen::VectorXd& t) const {
  GraphScore g;
  if (!ok_) return g;
  const Eigen::VectorXd w = ProjectOut(t);
  const double information = w.squaredNorm();
  if (!(information > 0.0)) return g;
  const double score = w.dot(r_perp_);
  // The score's contributions per state from the residuals once the one-step magnitude is taken
  // out (as a regression's HAC uses its fitted residuals): under the alternative the raw
  // residuals still hold the term, which would inflate the variance and hide it.
  const double theta = -score / information;
  std::vector<double> contribution(states_, 0.0);
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    contribution[row_state_[i]] += w[i] * (r_perp_[i] + w[i] * theta);
  }
  const double robust_variance = BartlettLongRunVariance(contribution, &g.lag);
  g.tested = true;
  g.magnitude = theta;
  g.model_sd = 1.0 / std::sqrt(information);
  g.robust_sd = std::sqrt(robust_variance) / information;
  g.states = states_;
  return g;
}

Eigen::VectorXd GraphProjector::EffectColumn(int effect) const {
  // The data's column: the weak prior the model puts on a magnitude once it is switched on
  // (effect_prior) is not evidence about it.
  Eigen::VectorXd t = J_.col(effect_column_ + effect);
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    if (row_is_prior_[i]) t[i] = 0.0;
  }
  return t;
}

std::vector<GraphScore> GraphProjector::EffectScores() const {
  std::vector<GraphScore> out(effect_count_);
  for (int e = 0; e < static_cast<int>(effect_count_); ++e) {
    if (std::find(in_model_.begin(), in_model_.end(), e) != in_model_.end()) continue;
    out[e] = Test(EffectColumn(e));
  }
  return out;
}

void GraphProjector::AddForceColumn(const std::vector<double>& h, int column,
                                    std::vector<Eigen::Triplet<double>>* entries) const {
  // An external force enters where a_dist does in the model's equations: t = sum_k h_k
  // J(:, a_dist_k) over the accelerometer and dynamics rows.
  for (size_t k = 0; k < states_ && k < h.size(); ++k) {
    if (h[k] == 0.0 || !std::isfinite(h[k])) continue;
    for (Sparse::InnerIterator it(J_, ward::kStateSize * k + ward::kAdist); it; ++it) {
      if (row_is_model_[it.row()]) entries->emplace_back(it.row(), column, h[k] * it.value());
    }
  }
}

Eigen::VectorXd GraphProjector::ForceColumn(const std::vector<double>& h) const {
  std::vector<Eigen::Triplet<double>> entries;
  AddForceColumn(h, 0, &entries);
  Sparse t(J_.rows(), 1);
  t.setFromTriplets(entries.begin(), entries.end());
  return Eigen::VectorXd(t);
}

GraphScore GraphProjector::TestForce(const std::vector<double>& h) const {
  return Test(ForceColumn(h));
}

ProjectedBasis GraphProjector::ProjectForces(const std::vector<std::vector<double>>& shapes,
                                             const Eigen::VectorXd* column) const {
  const Eigen::Index columns = static_cast<Eigen::Index>(shapes.size()) + (column ? 1 : 0);
  ProjectedBasis out;
  out.score = Eigen::VectorXd::Zero(columns);
  out.gram = Eigen::MatrixXd::Zero(columns, columns);
  if (!ok_ || columns == 0) return out;
  // T: a basis's columns touch a few states' rows each.
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t j = 0; j < shapes.size(); ++j) {
    AddForceColumn(shapes[j], static_cast<int>(j), &entries);
  }
  if (column != nullptr) {
    if (column->size() != J_.rows()) {
      throw std::invalid_argument("graph score test: a column of " +
                                  std::to_string(column->size()) + " rows, the graph has " +
                                  std::to_string(J_.rows()));
    }
    const int last = static_cast<int>(columns - 1);
    for (Eigen::Index i = 0; i < column->size(); ++i) {
      if ((*column)[i] != 0.0) entries.emplace_back(static_cast<int>(i), last, (*column)[i]);
    }
  }
  RowSparse T(J_.rows(), columns);
  T.setFromTriplets(entries.begin(), entries.end());
  // W = T - N X with X = (N'N)^-1 N'T, formed explicitly (W'W from T'T - T'N X would lose the
  // part of T the nuisance cannot mimic to cancellation), a band of rows at a time: W's row i
  // is N's row i's few entries times rows of X, and the band's W'W and W'r are summed at once.
  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajorMatrix x = solver_.solve(Eigen::MatrixXd(N_.transpose() * T));
  constexpr Eigen::Index kBand = 2048;
  RowMajorMatrix w;
  for (Eigen::Index first = 0; first < T.rows(); first += kBand) {
    const Eigen::Index rows = std::min(kBand, T.rows() - first);
    w = T.middleRows(first, rows);
    w.noalias() -= N_rows_.middleRows(first, rows) * x;
    out.score.noalias() += w.transpose() * r_perp_.segment(first, rows);
    out.gram.selfadjointView<Eigen::Lower>().rankUpdate(w.transpose());
  }
  out.gram = Eigen::MatrixXd(out.gram.selfadjointView<Eigen::Lower>());
  return out;
}

std::vector<GraphScore> GraphScoreTests(WardProblem& problem, const std::vector<int>& in_model) {
  return GraphProjector(problem, in_model).EffectScores();
}

}  // namespace slipgraph
