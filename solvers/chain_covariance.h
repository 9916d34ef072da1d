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
// A global that only a stretch of the chain reads (a stiffness node of the tire law's walk, read
// by the states within 60 s of it) is "local": where such columns are most of the border, each
// is eliminated right after the last state that reads it, in a front that moves along the chain
// (a state, the next, the local columns open around them, and the rest of the border, the
// "tail"), so the states' share of memory and time does not grow with the number of nodes; the
// same recursion runs on the fronts, and S is the tail's Schur complement.
//
// ceres::Covariance (SPARSE_QR) takes 40 s for the 6300 states of a one-minute log; this takes
// milliseconds and is checked against it in a test. The Jacobian is loss-corrected, as the
// solver sees it.
#pragma once

#include <ceres/problem.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace slipgraph {

struct ChainCovariance {
  bool ok = false;
  std::string error;                    // why not (not a chain, not positive definite)
  std::vector<Eigen::MatrixXd> states;  // cov(x_k), one per state
  std::vector<Eigen::MatrixXd> next;    // cov(x_{k+1}, x_k), one per consecutive pair
  // cov of the global parameters, stacked (tangent space). Where some of them are local (read by
  // a stretch of the chain only: ChainLinearization::LocalBorderColumns), the entries between
  // two local columns that no state's front holds together are not computed: NaN.
  Eigen::MatrixXd globals;
};

// `states` in chain order; `globals` may be empty. All blocks must be in `problem`, not constant.
// The residual blocks are evaluated on `threads` threads (ChainLinearization::Linearize).
ChainCovariance ComputeChainCovariance(ceres::Problem* problem, const std::vector<double*>& states,
                                       const std::vector<double*>& globals, int threads = 1);

// One (damped) Gauss-Newton step on the same structure, from ChainLinearization::Step: the
// factorization of H (+ mu diag(H)) solves H dx = -J'r, the residuals and Jacobian
// loss-corrected as Ceres' own step sees them. The sliding window's low-latency solver
// (solvers/window_smoother.h, WindowSolver::kChainGaussNewton) and the batch's chain solver take
// it: Ceres rebuilds the program, the Jacobian's structure, J'J's structure and the sparse
// Cholesky's symbolic analysis on every Solve; a chain needs none of them.
struct ChainStep {
  bool ok = false;
  std::string error;
  double cost = 0.0;                    // 0.5 |r|^2 at the linearization point (loss-corrected)
  std::vector<Eigen::VectorXd> states;  // dx_k
  Eigen::VectorXd globals;              // dx of the globals, stacked
};

// The chain's Gauss-Newton model at the problem's current values, kept so that it can be solved
// with several dampings: Levenberg-Marquardt (solvers/chain_solver) retries a rejected step with
// more damping without evaluating the Jacobian again.
class ChainLinearization {
 public:
  ChainLinearization();
  ~ChainLinearization();
  ChainLinearization(ChainLinearization&&) noexcept;
  ChainLinearization& operator=(ChainLinearization&&) noexcept;

  // Evaluates every residual block at the current values (runs of states on `threads` threads;
  // the sums, and so the result to its last digit, do not depend on their number); false with
  // *error when a block cannot be evaluated or links states that are not neighbours. The cost
  // functions must be callable from several threads at once, as Ceres' own multi-threaded
  // evaluation requires. The blocks each run takes (their cost and loss functions and
  // parameters) are kept for the next call with the same problem, states, globals and number
  // of blocks: a problem whose blocks change between calls, their number kept, needs a new
  // ChainLinearization.
  bool Linearize(ceres::Problem* problem, const std::vector<double*>& states,
                 const std::vector<double*>& globals, std::string* error, int threads = 1);
  double cost() const;  // 0.5 |r|^2, loss-corrected
  // The cost at the problem's current values, over the blocks the last Linearize read (they must
  // not have changed since), summed in the same runs whatever the number of threads; false when
  // none was read, a block cannot be evaluated or the cost is not finite.
  bool Cost(double* cost, int threads = 1) const;
  // The globals' columns that only a stretch of the chain touches (the tire law's stiffness
  // nodes), eliminated along it rather than kept in a dense border; 0 before a linearization.
  int LocalBorderColumns() const;
  // J'r: each state's tangent coordinates in turn, then the globals', stacked.
  const std::vector<double>& gradient() const;
  // The step of (H + mu diag(H)) d = -J'r (mu = 0: Gauss-Newton); false with step->error when
  // that matrix is not positive definite. Keeps its factorization's storage for the next step.
  // `held` (one flag per column, in gradient()'s order; may be null) holds columns where they are:
  // a parameter at a bound that the gradient pushes against, whose step is 0 and whose coupling is
  // left out of the others'.
  bool Step(double mu, ChainStep* step, const std::vector<char>* held = nullptr) const;
  // The marginal covariances of the first `states` states (-1: all; the others' and `next` left
  // empty unless all) from the last Step's factorization: the linearization's own when that
  // step was undamped (mu 0) and held nothing. Not ok before a Step has succeeded.
  ChainCovariance LastStepCovariance(int states = -1) const;
  // -(J'r . d + d'H d / 2): the cost decrease the linear model predicts for the step d.
  double PredictedDecrease(const std::vector<Eigen::VectorXd>& states,
                           const Eigen::VectorXd& globals) const;
  // J'r . d: the cost's slope along the step d.
  double Slope(const std::vector<Eigen::VectorXd>& states, const Eigen::VectorXd& globals) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// How the solution would move if the residuals moved by t (one column per perturbation): at a
// minimum, where J'r = 0, the first-order shift is dx = -H^-1 J' t. With t the change a model
// constant's error of one sd makes to the residuals, dx dx' is that constant's share of the
// estimate's error covariance (a Schmidt "consider" covariance: the constant is not estimated,
// its uncertainty is accounted for). t is given on the blocks it moves: each column stacks the
// listed blocks' rows in their order (num_residuals each, loss-corrected as Problem::Evaluate
// gives residuals); the other residuals do not move. H and J' t are taken block by block, on
// `threads` threads for H, without the problem's whole Jacobian.
struct ResidualShifts {
  std::vector<ceres::ResidualBlockId> blocks;
  std::vector<Eigen::VectorXd> columns;
};
struct ChainSensitivity {
  bool ok = false;
  std::string error;
  std::vector<std::vector<Eigen::VectorXd>> states;  // [column][state]: dx_k
  std::vector<Eigen::VectorXd> globals;              // [column]: dx of the globals, stacked
};
ChainSensitivity ComputeChainSensitivity(ceres::Problem* problem,
                                         const std::vector<double*>& states,
                                         const std::vector<double*>& globals,
                                         const ResidualShifts& shifts, int threads = 1);

}  // namespace slipgraph
