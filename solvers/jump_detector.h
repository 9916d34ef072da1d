// Detection and estimation of a jump in a Kalman filter's (nearly) constant parameters: the
// generalized likelihood ratio of Willsky & Jones (1976, "A generalized likelihood ratio approach
// to the detection and estimation of jumps in linear systems"), with a Gaussian prior on the jump
// so the ratio is a Bayes factor.
//
// The filter estimates theta (N) from measurements z_k = h_k(theta) + w_k (M each), with
// innovation r_k, its covariance S_k, Jacobian H_k and gain K_k. If theta jumped by nu just
// before update tau and the filter does not know it, the jump leaves a deterministic part in
// every later estimate error, F_k nu, with F_tau = I and F <- (I - K_k H_k) F after each update
// (the filter absorbs the jump slowly when its covariance is small), and in every innovation,
// G_k nu with G_k = H_k F_k. Per hypothesis tau the detector keeps
//
//   d = sum G_k' S_k^-1 r_k,   C = sum G_k' S_k^-1 G_k,
//
// and with the prior nu ~ N(0, J) the log Bayes factor of "a jump at tau" over "no jump" is
//
//   ln B = d' (C + J^-1)^-1 d / 2 - ln det(I + J C) / 2,
//
// its jump estimate nu = (C + J^-1)^-1 d with covariance (C + J^-1)^-1. A jump is declared when
// the best hypothesis's ln B exceeds a threshold; the filter's estimate is then corrected by
// F nu and its covariance grown by F cov(nu) F', and the hypotheses restart.
//
// Measurements that share data (overlapping path segments) are not independent: `overlap` > 1
// divides each one's information (each datum counted `overlap` times).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <deque>

#include "model/option_check.h"

namespace slipgraph {

struct JumpDetectorOptions {
  double jump_sd = 0.05;          // prior sd of the jump in each parameter
  double log_bayes_factor = 6.9;  // ln B to declare a jump (ln 1000)
  int window = 40;                // hypotheses kept: jumps before the last `window` measurements
  int min_measurements = 2;       // a hypothesis is tested after this many measurements
  double overlap = 1.0;           // each datum enters this many measurements

  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const {
    return OptionCheck("JumpDetectorOptions", error)
        .Positive("jump_sd", jump_sd)
        .Require("log_bayes_factor", std::isfinite(log_bayes_factor), log_bayes_factor,
                 "must be finite")
        .AtLeast("window", window, 1)
        .AtLeast("min_measurements", min_measurements, 1)
        .Positive("overlap", overlap);
  }
};

template <int N, int M>
class JumpDetector {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  using Jacobian = Eigen::Matrix<double, M, N>;
  using Residual = Eigen::Matrix<double, M, 1>;
  using Gain = Eigen::Matrix<double, N, M>;

  using Options = JumpDetectorOptions;

  struct Jump {
    double t = 0.0;  // the hypothesis's start (the update it precedes)
    double log_bayes_factor = 0.0;
    int measurements = 0;                // measurements since the jump
    Vector correction = Vector::Zero();  // F nu: add to the estimate
    Matrix covariance = Matrix::Zero();  // F cov(nu) F': add to its covariance
  };

  explicit JumpDetector(const Options& options) : options_(options) {
    std::string error;
    if (!options.IsValid(&error)) throw std::invalid_argument(error);
    J_inverse_ = Matrix::Identity() / (options.jump_sd * options.jump_sd);
  }

  // A measurement at time t before the filter uses it: residual r, Jacobian H and innovation
  // covariance S (with the filter's prior). Opens the hypothesis "a jump just before t". Returns
  // true and fills *jump when the best hypothesis passes the threshold (the caller applies the
  // correction and calls Restart(); it should not also update on this measurement: the
  // measurement is already in the jump's estimate).
  bool Measure(double t, const Residual& r, const Jacobian& H, const Eigen::Matrix<double, M, M>& S,
               Jump* jump) {
    hypotheses_.push_back({t, Matrix::Identity(), Vector::Zero(), Matrix::Zero(), 0});
    while (static_cast<int>(hypotheses_.size()) > options_.window) hypotheses_.pop_front();
    const Eigen::LDLT<Eigen::Matrix<double, M, M>> S_ldlt(S * options_.overlap);
    const Residual S_inv_r = S_ldlt.solve(r);
    double best = -1e300;
    const Hypothesis* best_h = nullptr;
    for (Hypothesis& h : hypotheses_) {
      const Jacobian G = H * h.F;
      h.d += G.transpose() * S_inv_r;
      h.C += G.transpose() * S_ldlt.solve(G);
      ++h.measurements;
      if (h.measurements < options_.min_measurements) continue;
      const double score = LogBayesFactor(h);
      if (score > best) best = score, best_h = &h;
    }
    if (best_h == nullptr || best < options_.log_bayes_factor) return false;
    const Eigen::LDLT<Matrix> A(best_h->C + J_inverse_);
    const Matrix cov = A.solve(Matrix::Identity());
    jump->t = best_h->t;
    jump->log_bayes_factor = best;
    jump->measurements = best_h->measurements;
    jump->correction = best_h->F * (cov * best_h->d);
    jump->covariance = best_h->F * cov * best_h->F.transpose();
    return true;
  }

  // The filter updated with gain K on the last measurement's Jacobian H (skip when it did not).
  void Updated(const Gain& K, const Jacobian& H) {
    const Matrix I_KH = Matrix::Identity() - K * H;
    for (Hypothesis& h : hypotheses_) h.F = I_KH * h.F;
  }

  // After a jump has been applied (or the filter was reset otherwise): no open hypotheses.
  void Restart() { hypotheses_.clear(); }

 private:
  struct Hypothesis {
    double t;
    Matrix F;
    Vector d;
    Matrix C;
    int measurements;
  };

  double LogBayesFactor(const Hypothesis& h) const {
    const Eigen::LDLT<Matrix> A(h.C + J_inverse_);
    const double quadratic = h.d.dot(A.solve(h.d));
    // det(I + J C) = det(J) det(C + J^-1): J = s^2 I.
    double log_det = N * std::log(options_.jump_sd * options_.jump_sd);
    const auto D = A.vectorD();
    for (int i = 0; i < N; ++i) log_det += std::log(D[i]);
    return 0.5 * quadratic - 0.5 * log_det;
  }

  Options options_;
  Matrix J_inverse_;
  std::deque<Hypothesis> hypotheses_;
};

}  // namespace slipgraph
