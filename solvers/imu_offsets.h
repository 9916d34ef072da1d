// Constant IMU offsets c_ax and c_gz of Ward & Iagnemma eq. (11): initialised as the mean of the
// first n IMU samples (with the gravity component removed from the accelerometer), then, whenever
// the robot is at rest, updated by the EMA of eq. (12).
//
// "At rest" is known late at both ends: the encoders read still (below the filter's threshold,
// which their quantization sets) while the body already creeps off, so the first samples of a
// start carry its acceleration (0.1-0.3 m/s^2 for a tenth of a second moved c_ax by 0.015 m/s^2
// on a simulated ward21 run, which the accelerometer-driven velocity then integrated into a 10
// cm/s drift). An at-rest sample therefore enters the EMA only once the robot has stayed at rest
// for rest_guard_s after it; the samples still waiting when motion is seen are dropped.
#pragma once

#include <deque>

#include "solvers/ema.h"

namespace slipgraph {

class ImuOffsetEstimator {
 public:
  ImuOffsetEstimator(int init_samples, double ema_samples, double rest_guard_s = 0.0);

  // One IMU sample at time t; gravity_along_x is g sin(phi) (phi uphill positive) at the sample;
  // at_rest says whether the robot is known to be stopped.
  void Add(double t, double accel_x_mps2, double gyro_z_radps, double gravity_along_x_mps2,
           bool at_rest);

  bool ready() const { return count_ >= init_samples_; }
  double accel_x_mps2() const { return accel_.value(); }
  double gyro_z_radps() const { return gyro_.value(); }

 private:
  struct Pending {
    double t, accel_offset, gyro_z;
  };
  int init_samples_;
  double rest_guard_s_;
  int count_ = 0;
  double sum_accel_ = 0.0, sum_gyro_ = 0.0;
  ExponentialMovingAverage accel_, gyro_;
  std::deque<Pending> pending_;  // at-rest samples younger than rest_guard_s
};

}  // namespace slipgraph
