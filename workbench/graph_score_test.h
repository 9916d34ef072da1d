// Rao's score (Lagrange-multiplier) test of a missing term on the whole factor graph at a
// smoother's solution.
//
// The smoother absorbs a missing force into what the model lets move: the velocity shifts a few
// mm/s, the slip follows, and the force balance closes again; a test that looks at one residual
// stream (the force balance against the effect's shape) then sees almost nothing. The score test
// on the graph does not: with J the whitened Jacobian of every factor at the solution, split into
// the nuisance columns N (states, IMU offsets, the effects already in the model) and the tested
// term's column t, and r the whitened residuals,
//
//   w = (I - N (N'N)^-1 N') t          the term's direction the nuisance cannot mimic
//   S = w' r,   I = w' w               efficient score and information
//   theta = -S / I,   sd = 1 / sqrt(I)  (one Gauss-Newton step from theta = 0)
//
// S^2 / I is chi-square with 1 dof under theta = 0 when the factors' sigmas are right. They are
// not exactly (quantized encoders, a disturbance walk that is a modelling device), so the test
// also gives a robust variance: S as a sum over states of c_k = sum over state k's rows of
// w_i e_i, e = r + w theta the residuals with the one-step magnitude taken out, and Var(S) from
// the Newey-West long-run variance of c_k (Boos 1992; Wooldridge's robust LM test). The
// workbench uses the larger of the two.
//
// The tested term is an effect term's column (factors/effect_term.h) or any external force
// shape h_k (m/s^2 per unit magnitude at state k), which enters the graph where the disturbance
// does in the model's own equations (the accelerometer and dynamics factors, not the
// disturbance's priors). A scan over many shapes (a patch of path) uses the projected basis: the
// score and the Gram matrix of the projected columns, so any sum of basis shapes is tested
// without another solve.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "problems/ward_batch_problem.h"

namespace slipgraph {

struct GraphScore {
  bool tested = false;     // false: in the model already, or the system was singular
  double magnitude = 0.0;  // one-step estimate -S / I, in the term's unit
  double model_sd = 0.0;   // 1 / sqrt(I): the factors' own sigmas
  double robust_sd = 0.0;  // sqrt(Var_HAC(S)) / I
  double lag = 0.0;        // the Bartlett bandwidth of the robust variance (states)
  size_t states = 0;
  double sd() const { return robust_sd > model_sd ? robust_sd : model_sd; }
};

// The projected scores and Gram matrix of a basis of force shapes.
struct ProjectedBasis {
  Eigen::VectorXd score;  // S_j = w_j' r
  Eigen::MatrixXd gram;   // w_i' w_j
};

class GraphProjector {
 public:
  // `problem` holds every effect term to test in its effect block and its parameter blocks are
  // set to the solution; `in_model` lists the indices (in WardProblem::effect_terms) of the terms
  // the user's model has (nuisance, not tested). Throws std::runtime_error when Ceres cannot
  // evaluate the problem.
  GraphProjector(WardProblem& problem, const std::vector<int>& in_model);

  bool ok() const { return ok_; }
  size_t states() const { return states_; }
  Eigen::Index rows() const { return J_.rows(); }  // the graph's residual rows (column length)

  // Each effect term not in the model, tested alone (the other candidates held at 0), in the
  // order of WardProblem::effect_terms.
  std::vector<GraphScore> EffectScores() const;
  // An external force of shape h (one value per state, m/s^2 per unit magnitude).
  GraphScore TestForce(const std::vector<double>& h) const;
  // A basis of external force shapes (each one value per state), projected; with `column` (a
  // raw column over the graph's residual rows, as EffectColumn's) appended last when not null.
  // Throws std::invalid_argument when that column's length is not rows().
  ProjectedBasis ProjectForces(const std::vector<std::vector<double>>& shapes,
                               const Eigen::VectorXd* column = nullptr) const;
  // Raw columns: a model effect's (its weak prior's rows zeroed: not data) and an external
  // force shape's.
  Eigen::VectorXd EffectColumn(int effect) const;
  Eigen::VectorXd ForceColumn(const std::vector<double>& h) const;

 private:
  using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
  GraphScore Test(const Eigen::VectorXd& t) const;
  // (I - N (N'N)^-1 N') T: the columns' part the nuisance cannot mimic.
  Eigen::MatrixXd ProjectOut(const Eigen::MatrixXd& T) const;
  // The force shape's column's entries (row, value) added to `entries` as column `column`.
  void AddForceColumn(const std::vector<double>& h, int column,
                      std::vector<Eigen::Triplet<double>>* entries) const;

  bool ok_ = false;
  size_t states_ = 0;
  std::vector<int> in_model_;
  std::vector<int> row_state_;
  std::vector<bool> row_is_model_;  // accelerometer and dynamics rows: where a force enters
  std::vector<bool> row_is_prior_;  // the effects' weak prior: not data
  Sparse J_, N_;
  RowSparse N_rows_;  // N again, row by row (ProjectForces)
  Eigen::VectorXd r_perp_;
  int effect_column_ = 0;
  size_t effect_count_ = 0;
  Eigen::SimplicialLDLT<Sparse> solver_;
};

// Convenience: GraphProjector(problem, in_model).EffectScores().
std::vector<GraphScore> GraphScoreTests(WardProblem& problem, const std::vector<int>& in_model);

}  // namespace slipgraph
