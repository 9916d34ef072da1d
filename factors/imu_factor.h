// IMU factors, Ward & Iagnemma eq. (11), rows 1 and 2:
//
//   accelerometer: r = (a_x - (f_tire(x) + c_ax + b_ax + a_dist)) / sd_a
//   yaw gyro:      r = (w_z - (yaw_rate + c_gz + b_gz)) / sd_g
//
// Parameter blocks: x_k (7), IMU offsets [c_ax, c_gz] (2). Inputs: the attitude at the sample
// (REP-103 roll and pitch, rad). sd_a includes the tire law's uncertainty
// (ModelConfig::tire_uncertainty) when the accelerometer also drives the velocity.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include "factors/ward_measurement.h"

namespace slipgraph {

// What every accelerometer factor of eq. (11) holds: the physics, the attitude's normal forces
// and g sin(phi) (computed once), the reading and its weight. Residual() is the row given the
// model's tire balance at the state (f_tire, with whatever terms a variant adds).
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

struct AccelerometerFactor {
  AccelerometerFactor(const ward::Params& params, const ward::Attitude<double>& attitude,
                      double accel_x_mps2, double sd_mps2)
      : reading_(params, attitude, accel_x_mps2, sd_mps2) {}

  template <typename T>
  bool operator()(const T* x, const T* offsets, T* residual) const {
    const ward::TireForces<T> forces = ward::ComputeTireForces(x, reading_.loads, reading_.params);
    residual[0] = reading_.Residual(forces.f_tire_mps2, x, offsets);
    return true;
  }

  static ceres::CostFunction* Create(const ward::Params& params,
                                     const ward::Attitude<double>& attitude, double accel_x_mps2,
                                     double sd_mps2) {
    return new ceres::AutoDiffCostFunction<AccelerometerFactor, 1, ward::kStateSize, 2>(
        new AccelerometerFactor(params, attitude, accel_x_mps2, sd_mps2));
  }

 private:
  AccelerometerReading reading_;
};

struct YawGyroFactor {
  YawGyroFactor(double gyro_z_radps, double sd_radps)
      : measured_(gyro_z_radps), sqrt_information_(1.0 / sd_radps) {}

  template <typename T>
  bool operator()(const T* x, const T* offsets, T* residual) const {
    residual[0] =
        sqrt_information_ * (measured_ - (x[ward::kYawRate] + offsets[1] + x[ward::kGyroBias]));
    return true;
  }

  static ceres::CostFunction* Create(double gyro_z_radps, double sd_radps) {
    return new ceres::AutoDiffCostFunction<YawGyroFactor, 1, ward::kStateSize, 2>(
        new YawGyroFactor(gyro_z_radps, sd_radps));
  }

 private:
  double measured_;
  double sqrt_information_;
};

}  // namespace slipgraph
