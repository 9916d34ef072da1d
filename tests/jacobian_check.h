// Jacobians of small templated functions by automatic differentiation (ceres::Jet) and by central
// differences, for checking the shared physics and, later, hand-written Jacobians.
#pragma once

#include <ceres/jet.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace slipgraph {
namespace testing {

// f(const T* x, T* y) with x of size N, y of size M.
template <int N, int M, typename F>
Eigen::Matrix<double, M, N> AutoDiffJacobian(const F& f, const double* x) {
  using Jet = ceres::Jet<double, N>;
  Jet x_jet[N];
  for (int i = 0; i < N; ++i) x_jet[i] = Jet(x[i], i);
  Jet y_jet[M];
  f(x_jet, y_jet);
  Eigen::Matrix<double, M, N> jacobian;
  for (int r = 0; r < M; ++r) jacobian.row(r) = y_jet[r].v.transpose();
  return jacobian;
}

template <int N, int M, typename F>
Eigen::Matrix<double, M, N> CentralDifferenceJacobian(const F& f, const double* x,
                                                      double relative_step = 1e-6) {
  Eigen::Matrix<double, M, N> jacobian;
  for (int c = 0; c < N; ++c) {
    double plus[N], minus[N];
    std::copy(x, x + N, plus);
    std::copy(x, x + N, minus);
    const double h = relative_step * std::max(1.0, std::abs(x[c]));
    plus[c] += h;
    minus[c] -= h;
    double y_plus[M], y_minus[M];
    f(plus, y_plus);
    f(minus, y_minus);
    for (int r = 0; r < M; ++r) jacobian(r, c) = (y_plus[r] - y_minus[r]) / (2.0 * h);
  }
  return jacobian;
}

// Largest entry-wise difference, relative to max(1, |entry|).
template <typename A, typename B>
double MaxRelativeDifference(const A& a, const B& b) {
  double worst = 0.0;
  for (int r = 0; r < a.rows(); ++r) {
    for (int c = 0; c < a.cols(); ++c) {
      const double scale = std::max(1.0, std::abs(b(r, c)));
      worst = std::max(worst, std::abs(a(r, c) - b(r, c)) / scale);
    }
  }
  return worst;
}

}  // namespace testing
}  // namespace slipgraph
