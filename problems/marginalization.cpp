#include "problems/marginalization.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <map>
#include <set>

namespace slipgraph {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Marginalization Marginalize(const ceres::Problem& problem, const std::vector<double*>& leaving) {
  Marginalization out;
  // The residual blocks to linearize, and the kept blocks they reach.
  std::set<ceres::ResidualBlockId> blocks;
  for (double* x : leaving) {
    std::vector<ceres::ResidualBlockId> ids;
    problem.GetResidualBlocksForParameterBlock(x, &ids);
    blocks.insert(ids.begin(), ids.end());
  }
  const std::set<double*> leaving_set(leaving.begin(), leaving.end());
  // Column layout: leaving blocks first, then kept blocks in order of first appearance.
  std::map<double*, int> column;
  int m = 0;
  for (double* x : leaving) {
    column[x] = m;
    m += problem.ParameterBlockSize(x);
  }
  int size = m;
  std::vector<ceres::ResidualBlockId> ordered(blocks.begin(), blocks.end());
  for (ceres::ResidualBlockId id : ordered) {
    std::vector<double*> parameters;
    problem.GetParameterBlocksForResidualBlock(id, &parameters);
    for (double* p : parameters) {
      if (column.count(p) != 0 || problem.IsParameterBlockConstant(p)) continue;
      column[p] = size;
      size += problem.ParameterBlockSize(p);
      out.kept.push_back(p);
    }
  }

  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(size, size);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(size);
  for (ceres::ResidualBlockId id : ordered) {
    std::vector<double*> parameters;
    problem.GetParameterBlocksForResidualBlock(id, &parameters);
    const int rows = problem.GetCostFunctionForResidualBlock(id)->num_residuals();
    std::vector<RowMajor> jacobians;
    std::vector<double*> jacobian_ptrs;
    for (double* p : parameters) {
      jacobians.emplace_back(rows, problem.ParameterBlockSize(p));
    }
    for (size_t i = 0; i < parameters.size(); ++i) {
      jacobian_ptrs.push_back(
          problem.IsParameterBlockConstant(parameters[i]) ? nullptr : jacobians[i].data());
    }
    Eigen::VectorXd residual(rows);
    double cost = 0.0;
    if (!problem.EvaluateResidualBlock(id, true, &cost, residual.data(), jacobian_ptrs.data()) ||
        !residual.allFinite()) {
      out.kept.clear();
      out.error = "a residual block could not be evaluated at the current values";
      return out;
    }
    for (size_t i = 0; i < parameters.size(); ++i) {
      if (jacobian_ptrs[i] == nullptr) continue;
      const int ci = column.at(parameters[i]);
      const int ni = static_cast<int>(jacobians[i].cols());
      b.segment(ci, ni) += jacobians[i].transpose() * residual;
      for (size_t j = 0; j < parameters.size(); ++j) {
        if (jacobian_ptrs[j] == nullptr) continue;
        const int cj = column.at(parameters[j]);
        H.block(ci, cj, ni, jacobians[j].cols()) += jacobians[i].transpose() * jacobians[j];
      }
    }
  }
  if (!H.allFinite() || !b.allFinite()) {
    out.kept.clear();
    out.error = "the linearized system is not finite";
    return out;
  }

  // Schur complement with a pseudo-inverse of H_mm (directions it does not constrain are dropped).
  const int k = size - m;
  if (k == 0) return out;  // nothing kept touches the leaving blocks: nothing to carry
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(H.topLeftCorner(m, m));
  const Eigen::VectorXd& s = eigen.eigenvalues();
  const double floor = 1e-12 * std::max(s.maxCoeff(), 0.0);
  Eigen::VectorXd s_inv = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < m; ++i) {
    if (s[i] > floor && s[i] > 0.0) s_inv[i] = 1.0 / s[i];
  }
  const Eigen::MatrixXd Hmm_inv =
      eigen.eigenvectors() * s_inv.asDiagonal() * eigen.eigenvectors().transpose();
  const Eigen::MatrixXd Hkm = H.bottomLeftCorner(k, m);
  const Eigen::MatrixXd H_prior = H.bottomRightCorner(k, k) - Hkm * Hmm_inv * Hkm.transpose();
  const Eigen::VectorXd b_prior = b.tail(k) - Hkm * Hmm_inv * b.head(m);

  std::vector<int> sizes;
  Eigen::VectorXd x0(k);
  int offset = 0;
  for (double* p : out.kept) {
    const int n = problem.ParameterBlockSize(p);
    sizes.push_back(n);
    x0.segment(offset, n) = Eigen::Map<const Eigen::VectorXd>(p, n);
    offset += n;
  }
  out.prior = std::make_unique<MarginalPrior>(sizes, x0, H_prior, b_prior);
  return out;
}

}  // namespace slipgraph
