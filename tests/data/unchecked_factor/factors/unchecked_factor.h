// The control of scripts/check-jacobian-tests: a cost function that no test checks.
#pragma once

#include <ceres/autodiff_cost_function.h>

struct UncheckedFactor {
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = x[0] * x[0];
    return true;
  }
  static ceres::CostFunction* Create() {
    return new ceres::AutoDiffCostFunction<UncheckedFactor, 1, 1>(new UncheckedFactor);
  }
};
