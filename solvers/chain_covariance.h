// Marginal covariances of a chain: states x_0..x_{n-1} of one size, where every residual block
// touches at most two consecutive states, plus a few global parameters (the IMU offsets) that
// any block may touch. The Gauss-Newton information H = J^T J is then block tridiagonal with a
// dense border,
//
//   H = [ T  B ]      T: block tridiagonal (states), B: states x globals, C: globals,
//       [ B' C ],
//
// and the diagonal blocks of H^-1 follow in O(n) from a block LDL' of T and Takahashi's
// recursion (Sigma_kk = D_k^-1 - N_k' Sigma_{k+1,k}, Sigma_{k+1,k} = -Sigma_{k+1,k+1} N_k),
// corrected for the border through the Schur complement S = C - B' T^-1 B:
//
//   cov(x_k) = Sigma_kk + X_k S^-1 X_k',   X = T^-1 B,     cov(globals) = S^-1.
//
// ceres::Covariance (SPARSE_QR) takes 40 s for the 6300 states of a one-minute log; this takes
// milliseconds and is checked against it in a test. The Jacobian is loss-corrected, as the
// solver sees it.
#pragma once

#include <ceres/problem.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace slipgraph {

struct ChainCovariance {
  bool ok = false;
  std::string error;                    // why not (not a chain, not positive definite)
  std::vector<Eigen::MatrixXd> states;  // cov(x_k), one per state
  std::vector<Eigen::MatrixXd> next;    // cov(x_{k+1}, x_k), one per consecutive pair
  Eigen::MatrixXd globals;              // cov of the global parameters, stacked (tangent space)
};

// `states` in chain order; `globals` may be empty. All blocks must be in `problem`, not constant.
ChainCovariance ComputeChainCovariance(ceres::Problem* problem, const std::vector<double*>& states,
                                       const std::vector<double*>& globals);

}  // namespace slipgraph
