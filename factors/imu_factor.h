// IMU factors, Ward & Iagnemma eq. (11): the accelerometer's reading (row 1; the factor is
// factors/accelerometer_factor.h) and the yaw gyro (row 2),
//
//   yaw gyro: r = (w_z - (yaw_rate + c_gz + b_gz)) / sd_g
//
// Parameter blocks: x_k (7), IMU offsets [c_ax, c_gz] (2).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/component_autodiff.h"
#include "factors/ward_measurement.h"

namespace slipgraph {

// What the accelerometer factor of eq. (11) holds: the physics, the attitude's normal forces
// and g sin(phi) (computed once), the reading and its weight. Residual() is the row given the
// model's tire balance at the state (f_tire, with whatever unknowns the problem gives it).
struct AccelerometerReading {
  AccelerometerReading(const ward::Params& params_in, const ward::Attitude<double>& attitude,
                       double accel_x_mps2, double sd_mps2)
      : params(params_in),
        loads(ward::ComputeAttitudeLoads(attitude, params_in)),
        measured(accel_x_mps2),
        sqrt_information(1.0 / sd_mps2) {}

  template <typename T>
  T Residual(const T& tire_balance, const T* x, const T* offsets) const {
    const T predicted = tire_balance + offsets[0] + x[ward::kAccelBias] + x[ward::kAdist];
    return sqrt_information * (measured - predicted);
  }

  ward::Params params;
  ward::AttitudeLoads<double> loads;
  double measured;
  double sqrt_information;
};

struct YawGyroFactor {
  static constexpr int kGyroOffset = 1;  // c_gz in the offsets block [c_ax, c_gz]

  YawGyroFactor(double gyro_z_radps, double sd_radps)
      : measured_(gyro_z_radps), sqrt_information_(1.0 / sd_radps) {}

  template <typename T>
  bool operator()(const T* x, const T* offsets, T* residual) const {
    residual[0] = sqrt_information_ *
                  (measured_ - (x[ward::kYawRate] + offsets[kGyroOffset] + x[ward::kGyroBias]));
    return true;
  }

  // The components operator() reads (factors/component_autodiff.h).
  struct Reads {
    static constexpr std::array<BlockComponent, 3> kComponents{
        {{0, ward::kYawRate}, {0, ward::kGyroBias}, {1, kGyroOffset}}};
  };
  static ceres::CostFunction* Create(double gyro_z_radps, double sd_radps) {
    return new ComponentAutoDiffCostFunction<YawGyroFactor, Reads, 1, ward::kStateSize, 2>(
        new YawGyroFactor(gyro_z_radps, sd_radps));
  }

 private:
  double measured_;
  double sqrt_information_;
};

}  // namespace slipgraph
