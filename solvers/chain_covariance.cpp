#include "solvers/chain_covariance.h"

#include <ceres/crs_matrix.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace slipgraph {

using Eigen::MatrixXd;

ChainCovariance ComputeChainCovariance(ceres::Problem* problem, const std::vector<double*>& states,
                                       const std::vector<double*>& globals) {
  ChainCovariance out;
  const int n = static_cast<int>(states.size());
  if (n == 0) {
    out.error = "no states";
    return out;
  }
  const int m = problem->ParameterBlockSize(states[0]);
  int g = 0;
  for (double* p : globals) g += problem->ParameterBlockTangentSize(p);
  for (double* x : states) {
    if (problem->ParameterBlockSize(x) != m) {
      out.error = "the states differ in size";
      return out;
    }
  }

  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = states;
  options.parameter_blocks.insert(options.parameter_blocks.end(), globals.begin(), globals.end());
  options.apply_loss_function = true;
  ceres::CRSMatrix J;
  if (!problem->Evaluate(options, nullptr, nullptr, nullptr, &J)) {
    out.error = "the Jacobian could not be evaluated";
    return out;
  }

  // Assemble the blocks of H = J' J: D[k] = T_kk, U[k] = T_{k,k+1}, B[k] = H_{k,globals}, C.
  std::vector<MatrixXd> D(n, MatrixXd::Zero(m, m)), U(n, MatrixXd::Zero(m, m)),
      B(n, MatrixXd::Zero(m, g));
  MatrixXd C = MatrixXd::Zero(g, g);
  const int state_columns = n * m;
  for (int row = 0; row < J.num_rows; ++row) {
    const int begin = J.rows[row], end = J.rows[row + 1];
    for (int a = begin; a < end; ++a) {
      const int ca = J.cols[a];
      const double va = J.values[a];
      for (int b = begin; b < end; ++b) {
        const int cb = J.cols[b];
        if (cb < ca) continue;  // upper triangle of H only
        const double v = va * J.values[b];
        if (ca >= state_columns) {
          C(ca - state_columns, cb - state_columns) += v;
          if (ca != cb) C(cb - state_columns, ca - state_columns) += v;
          continue;
        }
        const int ka = ca / m, ia = ca % m;
        if (cb >= state_columns) {
          B[ka](ia, cb - state_columns) += v;
          continue;
        }
        const int kb = cb / m, ib = cb % m;
        if (kb == ka) {
          D[ka](ia, ib) += v;
          if (ia != ib) D[ka](ib, ia) += v;
        } else if (kb == ka + 1) {
          U[ka](ia, ib) += v;
        } else {
          out.error = "a residual block links states " + std::to_string(ka) + " and " +
                      std::to_string(kb) + ": not a chain";
          return out;
        }
      }
    }
  }

  // Block LDL' of T: D_k <- pivots, N_k = T_{k+1,k} D_k^-1.
  std::vector<MatrixXd> N(n), D_inv(n);
  for (int k = 0; k < n; ++k) {
    if (k > 0) D[k] -= N[k - 1] * U[k - 1];
    Eigen::LLT<MatrixXd> llt(D[k]);
    if (llt.info() != Eigen::Success) {
      out.error = "the information of state " + std::to_string(k) +
                  " is not positive definite (a direction no factor constrains)";
      return out;
    }
    D_inv[k] = llt.solve(MatrixXd::Identity(m, m));
    if (k + 1 < n) N[k] = U[k].transpose() * D_inv[k];
  }
  // Takahashi: diagonal (and first sub-diagonal) blocks of T^-1, from the last state back.
  out.states.assign(n, MatrixXd());
  out.next.assign(n > 0 ? n - 1 : 0, MatrixXd());
  out.states[n - 1] = D_inv[n - 1];
  for (int k = n - 2; k >= 0; --k) {
    const MatrixXd sub = -out.states[k + 1] * N[k];  // Sigma_{k+1,k}
    out.next[k] = sub;
    out.states[k] = D_inv[k] - N[k].transpose() * sub;
  }
  if (g == 0) {
    out.ok = true;
    return out;
  }
  // The border: X = T^-1 B by forward and back substitution, S = C - B' X.
  std::vector<MatrixXd> X(n);
  for (int k = 0; k < n; ++k) X[k] = k > 0 ? MatrixXd(B[k] - N[k - 1] * X[k - 1]) : B[0];
  for (int k = 0; k < n; ++k) X[k] = D_inv[k] * X[k];
  for (int k = n - 2; k >= 0; --k) X[k] -= N[k].transpose() * X[k + 1];
  MatrixXd S = C;
  for (int k = 0; k < n; ++k) S -= B[k].transpose() * X[k];
  Eigen::LLT<MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) {
    out.error = "the global parameters' information is not positive definite";
    return out;
  }
  out.globals = llt.solve(MatrixXd::Identity(g, g));
  for (int k = 0; k < n; ++k) out.states[k] += X[k] * out.globals * X[k].transpose();
  for (int k = 0; k + 1 < n; ++k) out.next[k] += X[k + 1] * out.globals * X[k].transpose();
  out.ok = true;
  return out;
}

}  // namespace slipgraph
