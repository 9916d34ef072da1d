// The accelerometer factor of a model with physical effects switched on (factors/model_effects.h):
//
//   r = (a_x - (f_tire(x; theta) + c_ax + b_ax + a_dist)) / sd_a
//
// Parameter blocks: x_k (7), IMU offsets [c_ax, c_gz] (2), effect magnitudes theta
// (kModelEffectCount; the problem holds the inactive ones constant at 0). With theta = 0 it is
// AccelerometerFactor exactly (tests/model_effects_test.cpp). windows: the windowed effects'
// weights at the sample (EffectWindowWeightsAt).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/imu_factor.h"
#include "factors/model_effects.h"

namespace slipgraph {

struct EffectAccelerometerFactor {
  EffectAccelerometerFactor(const ward::Params& params, const ward::Attitude<double>& attitude,
                            double accel_x_mps2, double sd_mps2,
                            const EffectWindowWeights& windows = {})
      : reading_(params, attitude, accel_x_mps2, sd_mps2), attitude_(attitude), windows_(windows) {}

  template <typename T>
  bool operator()(const T* x, const T* offsets, const T* theta, T* residual) const {
    residual[0] = reading_.Residual(
        TireBalanceWithEffects(x, attitude_, reading_.loads, reading_.params, theta, windows_), x,
        offsets);
    return true;
  }

  static ceres::CostFunction* Create(const ward::Params& params,
                                     const ward::Attitude<double>& attitude, double accel_x_mps2,
                                     double sd_mps2, const EffectWindowWeights& windows = {}) {
    return new ceres::AutoDiffCostFunction<EffectAccelerometerFactor, 1, ward::kStateSize, 2,
                                           kModelEffectCount>(
        new EffectAccelerometerFactor(params, attitude, accel_x_mps2, sd_mps2, windows));
  }

 private:
  AccelerometerReading reading_;
  ward::Attitude<double> attitude_;
  EffectWindowWeights windows_;
};

}  // namespace slipgraph
