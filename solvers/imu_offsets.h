// Constant IMU offsets c_ax and c_gz of Ward & Iagnemma eq. (11): initialised as the mean of the
// first n IMU samples (with the gravity component removed from the accelerometer), then, whenever
// the robot is at rest, updated by the EMA of eq. (12).
#pragma once

#include "solvers/ema.h"

namespace slipgraph {

class ImuOffsetEstimator {
 public:
  ImuOffsetEstimator(int init_samples, double ema_samples);

  // One IMU sample; gravity_along_x is g sin(phi) (phi uphill positive) at the sample; at_rest
  // says whether the robot is known to be stopped.
  void Add(double accel_x_mps2, double gyro_z_radps, double gravity_along_x_mps2, bool at_rest);

  bool ready() const { return count_ >= init_samples_; }
  double accel_x_mps2() const { return accel_.value(); }
  double gyro_z_radps() const { return gyro_.value(); }

 private:
  int init_samples_;
  int count_ = 0;
  double sum_accel_ = 0.0, sum_gyro_ = 0.0;
  ExponentialMovingAverage accel_, gyro_;
};

}  // namespace slipgraph
