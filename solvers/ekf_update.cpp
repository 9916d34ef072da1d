#include "solvers/ekf_update.h"

#include <Eigen/Cholesky>
#include <cassert>
#include <cmath>

namespace slipgraph {
namespace ekf {

void MeasurementRows::Add(double innovation, const StateRow& h, double variance, const char* name) {
  assert(size_ < kMaxRows);
  nu_[size_] = innovation;
  h_[size_] = h;
  r_[size_] = variance;
  names_[size_] = name;
  // A unit row on one state reads a column of P instead of a product.
  int unit = -1;
  for (int j = 0; j < kStateSize && unit != -2; ++j) {
    if (h(j) != 0.0) unit = (unit == -1 && h(j) == 1.0) ? j : -2;
  }
  on_state_[size_] = unit >= 0 ? unit : -1;
  ++size_;
}

void MeasurementRows::AddOnState(int index, double innovation, double variance, const char* name) {
  Add(innovation, StateRow::Unit(index), variance, name);
}

double InnovationDistance::LogLikelihood(int rows) const {
  return -0.5 * (mahalanobis + std::log(det_s) + rows * std::log(2.0 * M_PI));
}

InnovationDistance DistanceOf(const MeasurementRows& rows, const StateMatrix& P) {
  const int m = rows.size();
  using RowSquare = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;
  using RowVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxRows, 1>;
  RowSquare S(m, m);
  RowVector nu(m);
  for (int i = 0; i < m; ++i) {
    const StateVector Ph = P * rows.jacobian(i).transpose();
    for (int j = 0; j <= i; ++j) S(j, i) = S(i, j) = rows.jacobian(j).dot(Ph);
    S(i, i) += rows.variance(i);
    nu(i) = rows.innovation(i);
  }
  // One or two rows (every stream but a stacked custom one): closed form, no factorization.
  InnovationDistance d;
  if (m == 1) {
    d.det_s = S(0, 0);
    d.mahalanobis = nu(0) * nu(0) / S(0, 0);
  } else if (m == 2) {
    d.det_s = S(0, 0) * S(1, 1) - S(0, 1) * S(1, 0);
    d.mahalanobis =
        (S(1, 1) * nu(0) * nu(0) - (S(0, 1) + S(1, 0)) * nu(0) * nu(1) + S(0, 0) * nu(1) * nu(1)) /
        d.det_s;
  } else {
    const auto ldlt = S.ldlt();
    d.det_s = ldlt.vectorD().prod();
    d.mahalanobis = nu.dot(ldlt.solve(nu));
  }
  return d;
}

double ApplySequentialUpdate(const MeasurementRows& rows, bool want_likelihood, StateVector* x,
                             StateMatrix* P, double* normalized, double* measurement_share) {
  // Each row in Joseph form P = A P A' + r k k', A = I - k h', evaluated in O(n^2):
  // A P = P - k (P h)', (A P) A' = A P - (A P h) k'.
  double log_likelihood = 0.0;
  const StateVector x_prior = *x;
  for (int i = 0; i < rows.size(); ++i) {
    const StateVector h = rows.jacobian(i).transpose();
    // The stacked update's linearization at x_prior: the innovation moves with the earlier rows.
    const double innovation = rows.innovation(i) - h.dot(*x - x_prior);
    const int unit = rows.on_state(i);
    const StateVector Ph = unit >= 0 ? StateVector(P->col(unit)) : StateVector(*P * h);
    const double r = rows.variance(i);
    const double s = h.dot(Ph) + r;
    const StateVector k = Ph / s;
    if (want_likelihood) {
      log_likelihood -= 0.5 * (innovation * innovation / s + std::log(2.0 * M_PI * s));
    }
    if (normalized != nullptr) normalized[i] = innovation / std::sqrt(s);
    if (measurement_share != nullptr) measurement_share[i] = r / s;
    *x += k * innovation;
    P->noalias() -= k * Ph.transpose();  // A P
    const StateVector APh = unit >= 0 ? StateVector(P->col(unit)) : StateVector(*P * h);
    P->noalias() -= (APh - r * k) * k.transpose();  // (A P) A' + r k k'
  }
  return log_likelihood;
}

}  // namespace ekf
}  // namespace slipgraph
