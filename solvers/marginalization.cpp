#include "solvers/marginalization.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <set>

namespace slipgraph {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

namespace {

// One residual block linearized at the current values (loss-corrected); a constant parameter
// block has an empty Jacobian.
struct LinearizedBlock {
  std::vector<double*> parameters;
  Eigen::VectorXd residual;
  std::vector<RowMajor> jacobians;
};

// An order of the blocks that depends on their values only, never on where they sit in memory
// (the problem hands them out by address): the sums below then come out the same, to the bit,
// in every run and build. Blocks equal in every value add the same numbers in any order; only
// the order of the kept blocks they alone reach can then follow the problem's.
bool ValueOrder(const LinearizedBlock& a, const LinearizedBlock& b) {
  const auto by_value = [](const auto& x, const auto& y) {
    if (x.size() != y.size()) return x.size() < y.size();
    return std::lexicographical_compare(x.data(), x.data() + x.size(), y.data(),
                                        y.data() + y.size());
  };
  if (a.residual.size() != b.residual.size()) return a.residual.size() < b.residual.size();
  if (a.jacobians.size() != b.jacobians.size()) return a.jacobians.size() < b.jacobians.size();
  if (by_value(a.residual, b.residual)) return true;
  if (by_value(b.residual, a.residual)) return false;
  for (size_t i = 0; i < a.jacobians.size(); ++i) {
    if (by_value(a.jacobians[i], b.jacobians[i])) return true;
    if (by_value(b.jacobians[i], a.jacobians[i])) return false;
  }
  return false;
}

}  // namespace

Marginalization Marginalize(const ceres::Problem& problem, const std::vector<double*>& leaving) {
  Marginalization out;
  // The residual blocks to linearize (each once), evaluated, then put in value order.
  std::set<ceres::ResidualBlockId> blocks;
  for (double* x : leaving) {
    std::vector<ceres::ResidualBlockId> ids;
    problem.GetResidualBlocksForParameterBlock(x, &ids);
    blocks.insert(ids.begin(), ids.end());
  }
  std::vector<LinearizedBlock> linearized;
  linearized.reserve(blocks.size());
  for (ceres::ResidualBlockId id : blocks) {
    LinearizedBlock block;
    problem.GetParameterBlocksForResidualBlock(id, &block.parameters);
    const int rows = problem.GetCostFunctionForResidualBlock(id)->num_residuals();
    std::vector<double*> jacobian_ptrs;
    for (double* p : block.parameters) {
      const bool constant = problem.IsParameterBlockConstant(p);
      block.jacobians.emplace_back(rows, constant ? 0 : problem.ParameterBlockSize(p));
      jacobian_ptrs.push_back(constant ? nullptr : block.jacobians.back().data());
    }
    block.residual.resize(rows);
    double cost = 0.0;
    if (!problem.EvaluateResidualBlock(id, true, &cost, block.residual.data(),
                                       jacobian_ptrs.data()) ||
        !block.residual.allFinite()) {
      out.error = "a residual block could not be evaluated at the current values";
      return out;
    }
    for (const RowMajor& jacobian : block.jacobians) {
      if (!jacobian.allFinite()) {
        out.error = "the linearized system is not finite";
        return out;
      }
    }
    linearized.push_back(std::move(block));
  }
  std::sort(linearized.begin(), linearized.end(), ValueOrder);

  // Column layout: leaving blocks first, then kept blocks in order of first appearance.
  std::map<double*, int> column;
  int m = 0;
  for (double* x : leaving) {
    column[x] = m;
    m += problem.ParameterBlockSize(x);
  }
  int size = m;
  for (const LinearizedBlock& block : linearized) {
    for (size_t i = 0; i < block.parameters.size(); ++i) {
      double* p = block.parameters[i];
      if (column.count(p) != 0 || block.jacobians[i].cols() == 0) continue;
      column[p] = size;
      size += problem.ParameterBlockSize(p);
      out.kept.push_back(p);
    }
  }

  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(size, size);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(size);
  for (const LinearizedBlock& block : linearized) {
    const std::vector<RowMajor>& jacobians = block.jacobians;
    for (size_t i = 0; i < block.parameters.size(); ++i) {
      if (jacobians[i].cols() == 0) continue;
      const int ci = column.at(block.parameters[i]);
      const int ni = static_cast<int>(jacobians[i].cols());
      b.segment(ci, ni) += jacobians[i].transpose() * block.residual;
      for (size_t j = 0; j < block.parameters.size(); ++j) {
        if (jacobians[j].cols() == 0) continue;
        const int cj = column.at(block.parameters[j]);
        H.block(ci, cj, ni, jacobians[j].cols()) += jacobians[i].transpose() * jacobians[j];
      }
    }
  }
  if (!H.allFinite() || !b.allFinite()) {
    out.kept.clear();
    out.error = "the linearized system is not finite";
    return out;
  }

  // Schur complement with a pseudo-inverse of H_mm (directions it does not constrain are dropped;
  // its inverse where it has full rank).
  const int k = size - m;
  if (k == 0) return out;  // nothing kept touches the leaving blocks: nothing to carry
  constexpr double kEigenFloor = 1e-12;
  const Eigen::MatrixXd Hmm = H.topLeftCorner(m, m);
  Eigen::LLT<Eigen::MatrixXd> llt;
  Eigen::MatrixXd Hmm_inv;
  if (!FullRankInverse(Hmm, kEigenFloor, &llt, &Hmm_inv)) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Hmm);
    const Eigen::VectorXd& s = eigen.eigenvalues();
    const double floor = kEigenFloor * std::max(s.maxCoeff(), 0.0);
    Eigen::VectorXd s_inv = Eigen::VectorXd::Zero(m);
    for (int i = 0; i < m; ++i) {
      if (s[i] > floor && s[i] > 0.0) s_inv[i] = 1.0 / s[i];
    }
    Hmm_inv = eigen.eigenvectors() * s_inv.asDiagonal() * eigen.eigenvectors().transpose();
  }
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
