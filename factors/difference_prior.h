// Gaussian prior on the step between two parameter blocks of size N:
//
//   r = (b - a - mean) / sd
//
// The Wilcox graph's odometry prior on a rover's advance between cycles (N = 1, mean the
// odometry's advance) and the IPD graph's random walk of the slip model between path blocks
// (N = ipd::kAlphaSize, mean zero: the model drifts as the terrain changes).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <array>

namespace slipgraph {

template <int N>
struct DifferencePrior {
  DifferencePrior(const std::array<double, N>& mean, double sd)
      : mean_(mean), sqrt_information_(1.0 / sd) {}

  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    for (int i = 0; i < N; ++i) residual[i] = (b[i] - a[i] - mean_[i]) * sqrt_information_;
    return true;
  }

  static ceres::CostFunction* Create(const std::array<double, N>& mean, double sd) {
    return new ceres::AutoDiffCostFunction<DifferencePrior, N, N, N>(new DifferencePrior(mean, sd));
  }

 private:
  std::array<double, N> mean_;
  double sqrt_information_;
};

}  // namespace slipgraph
