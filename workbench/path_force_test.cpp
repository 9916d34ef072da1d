#include "workbench/path_force_test.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "factors/ward_state.h"
#include "workbench/robust_statistics.h"

namespace slipgraph {

std::pair<double, int> ChiSquareOfScores(const Eigen::VectorXd& score,
                                         const Eigen::MatrixXd& gram) {
  if (score.size() == 0) return {0.0, 0};
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
  const double largest = eigen.eigenvalues().maxCoeff();
  if (!(largest > 0.0)) return {0.0, 0};
  const Eigen::VectorXd along = eigen.eigenvectors().transpose() * score;
  double x2 = 0.0;
  int rank = 0;
  for (Eigen::Index i = 0; i < along.size(); ++i) {
    if (eigen.eigenvalues()[i] > 1e-9 * largest) {
      x2 += along[i] * along[i] / eigen.eigenvalues()[i];
      ++rank;
    }
  }
  return {x2, rank};
}

PathForceTest TestForceAlongPath(const ModelResiduals& m, const Eigen::VectorXd* candidate_column,
                                 const std::string& candidate, double alpha, double metre,
                                 double window_m) {
  PathForceTest out;
  out.metre = metre;
  const size_t n = m.states.size();
  if (m.graph == nullptr || !m.graph->ok() || n < 2) return out;
  // The basis covers the states that move (a force on a robot at rest is the disturbance's
  // business, weak constraint 4).
  const std::vector<double> s = PathDistances(m);
  const size_t cells = static_cast<size_t>(std::floor(s.back() / metre)) + 1;
  std::vector<std::vector<double>> basis(cells, std::vector<double>(n, 0.0));
  std::vector<double> t_first(cells, NAN), t_last(cells, NAN);
  for (size_t k = 0; k < n; ++k) {
    if (std::abs(m.states[k].x[ward::kVbx]) < 0.05) continue;
    const size_t j = static_cast<size_t>(s[k] / metre);
    basis[j][k] = 1.0;
    if (std::isnan(t_first[j])) t_first[j] = m.states[k].t;
    t_last[j] = m.states[k].t;
  }
  // One projection serves the basis alone (its leading block) and, with the candidate's column
  // appended, the joint test.
  const bool with_candidate = candidate_column != nullptr;
  const ProjectedBasis joint = m.graph->ProjectForces(basis, candidate_column);
  const Eigen::Index nc = static_cast<Eigen::Index>(cells);
  const ProjectedBasis projected{joint.score.head(nc), joint.gram.topLeftCorner(nc, nc)};
  const auto [x2, rank] = ChiSquareOfScores(projected.score, projected.gram);
  if (rank == 0) return out;
  out.tested = true;
  out.statistic = x2;
  out.dof = rank;
  out.p_value = ChiSquareUpperTail(x2, rank);

  if (with_candidate) {
    // Joint with the candidate, minus the candidate alone: what is left after it.
    const auto [x2_joint, rank_joint] = ChiSquareOfScores(joint.score, joint.gram);
    const double own_information = joint.gram(nc, nc);
    const double own =
        own_information > 0.0 ? joint.score[nc] * joint.score[nc] / own_information : 0.0;
    out.after_effect = candidate;
    out.after_statistic = std::max(0.0, x2_joint - own);
    out.after_dof = std::max(0, rank_joint - (own_information > 0.0 ? 1 : 0));
    out.after_p_value =
        out.after_dof > 0 ? ChiSquareUpperTail(out.after_statistic, out.after_dof) : 1.0;
  }

  // Windows of window_m, 2 and 4 times that, and the whole path, stepping one cell; Bonferroni
  // over all of them. A force spread along the whole drive (a corrugated track) shows only at
  // the largest scale, a local one (a soft patch) at the smallest.
  std::vector<size_t> widths;
  for (double w = window_m; w < cells * metre; w *= 2.0) {
    widths.push_back(std::max<size_t>(1, static_cast<size_t>(std::lround(w / metre))));
    if (widths.size() == 3) break;
  }
  widths.push_back(cells);
  double windows = 0.0;
  for (size_t width : widths) windows += width <= cells ? cells - width + 1 : 0;
  struct Window {
    size_t a, b;
    double statistic, dof, p;
  };
  std::vector<Window> flagged;
  for (size_t width : widths) {
    for (size_t a = 0; a + width <= cells; ++a) {
      const auto [wx2, wrank] = ChiSquareOfScores(projected.score.segment(a, width),
                                                  projected.gram.block(a, a, width, width));
      if (wrank == 0) continue;
      const double p = std::min(1.0, ChiSquareUpperTail(wx2, wrank) * windows);
      if (p < alpha) flagged.push_back({a, a + width, wx2, static_cast<double>(wrank), p});
    }
  }
  std::sort(flagged.begin(), flagged.end(),
            [](const Window& x, const Window& y) { return x.a < y.a; });
  for (const Window& w : flagged) {
    double t0 = NAN, t1 = NAN;
    for (size_t j = w.a; j < w.b; ++j) {
      if (!std::isnan(t_first[j]) && std::isnan(t0)) t0 = t_first[j];
      if (!std::isnan(t_last[j])) t1 = t_last[j];
    }
    const double s0 = w.a * metre, s1 = w.b * metre;
    if (!out.stretches.empty() && s0 <= out.stretches.back().s_end) {
      PathForceTest::Stretch& last = out.stretches.back();
      if (s1 > last.s_end) {
        last.s_end = s1;
        if (!std::isnan(t1)) last.t_end = t1;
      }
      if (w.p < last.p_value) last.p_value = w.p, last.statistic = w.statistic, last.dof = w.dof;
    } else {
      out.stretches.push_back({s0, s1, t0, t1, w.statistic, w.dof, w.p});
    }
  }
  return out;
}

}  // namespace slipgraph
