// Gaussian prior with diagonal covariance on a parameter block of size N:
//
//   r = (x - mean) ./ sd
//
// Used for the first state (from the EKF's initial estimate and covariance) and for the constant
// IMU offsets (from the mean of the first IMU samples at rest, Ward & Iagnemma eq. 11-12).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <array>

namespace slipgraph {

template <int N>
struct DiagonalPrior {
  DiagonalPrior(const std::array<double, N>& mean, const std::array<double, N>& sd) : mean_(mean) {
    for (int i = 0; i < N; ++i) sqrt_information_[i] = 1.0 / sd[i];
  }

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int i = 0; i < N; ++i) residual[i] = sqrt_information_[i] * (x[i] - mean_[i]);
    return true;
  }

  static ceres::CostFunction* Create(const std::array<double, N>& mean,
                                     const std::array<double, N>& sd) {
    return new ceres::AutoDiffCostFunction<DiagonalPrior, N, N>(new DiagonalPrior(mean, sd));
  }

 private:
  std::array<double, N> mean_;
  std::array<double, N> sqrt_information_;
};

}  // namespace slipgraph
