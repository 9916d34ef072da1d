// The EKF's state (the 7 states of factors/ward_state.h with their covariance) and the one
// Kalman update every measurement goes through: the stacked innovation gated on its Mahalanobis
// distance, then its rows applied one after the other as scalar updates in Joseph form. R is
// diagonal, so the rows in sequence are the stacked update; each row is linearized at the state
// before the first (an iterated update would move it). Each row's log-likelihood and normalized
// innovation come back for a bank's weights and the consistency tests.
#pragma once

#include <Eigen/Core>
#include <array>

#include "factors/ward_state.h"

namespace slipgraph {
namespace ekf {

constexpr int kStateSize = ward::kStateSize;
constexpr int kMaxRows = 5;
using StateVector = Eigen::Matrix<double, kStateSize, 1>;
using StateMatrix = Eigen::Matrix<double, kStateSize, kStateSize>;
using StateRow = Eigen::Matrix<double, 1, kStateSize>;

// The rows of one measurement (at most kMaxRows): innovation nu = z - h(x), Jacobian row and
// noise variance each, and optionally each row's name for the recorded innovations.
class MeasurementRows {
 public:
  int size() const { return size_; }
  void Add(double innovation, const StateRow& h, double variance, const char* name = nullptr);
  // A row that measures one state directly (h = e_index): encoders, GNSS, weak constraints.
  void AddOnState(int index, double innovation, double variance, const char* name = nullptr);

  double innovation(int i) const { return nu_[i]; }
  const StateRow& jacobian(int i) const { return h_[i]; }
  double variance(int i) const { return r_[i]; }
  // The state a row measures directly, or -1.
  int on_state(int i) const { return on_state_[i]; }
  const char* name(int i) const { return names_[i]; }

 private:
  int size_ = 0;
  std::array<double, kMaxRows> nu_{}, r_{};
  std::array<StateRow, kMaxRows> h_;
  std::array<int, kMaxRows> on_state_{};
  std::array<const char*, kMaxRows> names_{};
};

// The stacked innovation's squared Mahalanobis distance nu' S^-1 nu, S = H P H' + R, and det S.
struct InnovationDistance {
  double mahalanobis = 0.0;
  double det_s = 1.0;
  // log N(nu; 0, S) of the whole measurement.
  double LogLikelihood(int rows) const;
};
InnovationDistance DistanceOf(const MeasurementRows& rows, const StateMatrix& P);

// Applies the rows to (x, P). Returns the sum of the rows' conditional log-likelihoods
// -0.5 (nu_i^2 / s_i + log 2 pi s_i) when `want_likelihood` (else 0: no logarithm taken);
// writes each row's normalized innovation nu_i / sqrt(s_i) to normalized[i] when given, and the
// measurement's share of its variance, r_i / s_i, to measurement_share[i] when given.
double ApplySequentialUpdate(const MeasurementRows& rows, bool want_likelihood, StateVector* x,
                             StateMatrix* P, double* normalized = nullptr,
                             double* measurement_share = nullptr);

}  // namespace ekf
}  // namespace slipgraph
