// The prior that marginalization leaves behind: a linear residual on the kept parameter blocks,
//
//   r(x) = r0 + J (x - x0),
//
// with x0 the linearization point and J, r0 chosen so that 0.5 |r|^2 has the Hessian H and the
// gradient b of the eliminated problem there: H = V S V^T (eigenvalues S > 0 kept),
// J = S^(1/2) V^T, r0 = S^(-1/2) V^T b; where H has full rank, its Cholesky factor gives the same
// cost more cheaply (H = L L', J = L', r0 = L^-1 b). Ceres has no built-in marginalization;
// VINS-Mono, OKVIS and fuse each write this cost function, as we do. Jacobians are analytic (J
// itself).
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace slipgraph {

// H^-1 from a Cholesky factorization when every eigenvalue of the symmetric H exceeds
// `eigen_floor` times the largest, which is then what the eigen-decomposition would keep: the
// smallest eigenvalue is at least 1 / |H^-1|_F, the largest at most the trace. False otherwise
// (the caller decomposes H and drops the directions below the floor). `llt` keeps H = L L'.
inline bool FullRankInverse(const Eigen::MatrixXd& H, double eigen_floor,
                            Eigen::LLT<Eigen::MatrixXd>* llt, Eigen::MatrixXd* inverse) {
  llt->compute(H);
  if (llt->info() != Eigen::Success) return false;
  *inverse = llt->solve(Eigen::MatrixXd::Identity(H.rows(), H.cols()));
  const double norm = inverse->norm();  // Frobenius
  return std::isfinite(norm) && norm > 0.0 && 1.0 / norm > eigen_floor * H.trace();
}

class MarginalPrior : public ceres::CostFunction {
 public:
  // block_sizes: sizes of the kept blocks, in the order they are passed to AddResidualBlock;
  // x0: their values stacked; H, b: Hessian and gradient over the stacked blocks at x0.
  // Eigen-directions with eigenvalue below eigen_floor * max eigenvalue carry no information and
  // are dropped (they are the null space of the eliminated problem).
  MarginalPrior(const std::vector<int>& block_sizes, const Eigen::VectorXd& x0,
                const Eigen::MatrixXd& H, const Eigen::VectorXd& b, double eigen_floor = 1e-12)
      : x0_(x0) {
    for (int size : block_sizes) mutable_parameter_block_sizes()->push_back(size);
    const Eigen::MatrixXd symmetric = 0.5 * (H + H.transpose());
    Eigen::LLT<Eigen::MatrixXd> llt;
    Eigen::MatrixXd inverse;
    if (FullRankInverse(symmetric, eigen_floor, &llt, &inverse)) {
      // H = L L': J = L', r0 = L^-1 b (J'J = H, J'r0 = b, as from the eigen-decomposition).
      J_ = llt.matrixU();
      r0_ = llt.matrixL().solve(b);
      set_num_residuals(static_cast<int>(r0_.size()));
      return;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(symmetric);
    const Eigen::VectorXd& s = eigen.eigenvalues();
    const double floor = eigen_floor * std::max(s.maxCoeff(), 0.0);
    std::vector<int> kept;
    for (int i = 0; i < s.size(); ++i) {
      if (s[i] > floor && s[i] > 0.0) kept.push_back(i);
    }
    const int m = static_cast<int>(kept.size());
    J_.resize(m, x0.size());
    r0_.resize(m);
    for (int row = 0; row < m; ++row) {
      const int i = kept[row];
      const double root = std::sqrt(s[i]);
      J_.row(row) = root * eigen.eigenvectors().col(i).transpose();
      r0_[row] = eigen.eigenvectors().col(i).dot(b) / root;
    }
    set_num_residuals(m > 0 ? m : 1);  // Ceres needs at least one residual
    if (m == 0) {
      J_ = Eigen::MatrixXd::Zero(1, x0.size());
      r0_ = Eigen::VectorXd::Zero(1);
    }
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    Eigen::VectorXd dx(x0_.size());
    int offset = 0;
    const std::vector<int32_t>& sizes = parameter_block_sizes();
    for (size_t block = 0; block < sizes.size(); ++block) {
      for (int i = 0; i < sizes[block]; ++i) {
        dx[offset + i] = parameters[block][i] - x0_[offset + i];
      }
      offset += sizes[block];
    }
    Eigen::Map<Eigen::VectorXd>(residuals, num_residuals()) = r0_ + J_ * dx;
    if (jacobians != nullptr) {
      offset = 0;
      for (size_t block = 0; block < sizes.size(); ++block) {
        if (jacobians[block] != nullptr) {
          Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
              jacobians[block], num_residuals(), sizes[block]) =
              J_.middleCols(offset, sizes[block]);
        }
        offset += sizes[block];
      }
    }
    return true;
  }

  int rank() const { return r0_.size() == 1 && J_.isZero() ? 0 : static_cast<int>(r0_.size()); }

 private:
  Eigen::VectorXd x0_;
  Eigen::MatrixXd J_;
  Eigen::VectorXd r0_;
};

}  // namespace slipgraph
