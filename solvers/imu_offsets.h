// Constant IMU offsets c_ax and c_gz of Ward & Iagnemma eq. (11): initialised over the first n
// IMU samples (with the gravity component removed from the accelerometer), then, whenever the
// robot is at rest, updated by the EMA of eq. (12).
//
// The start needs no rest. While the wheels read still, the samples are the paper's rest; when
// they turn before n samples, the rest so far is used if it is long enough (n / 4 samples, once
// the last tenth of a second before the motion is dropped: the encoders see a start late), and
// the motion is subtracted otherwise. Over n samples the accelerometer's mean is the offset plus
// the body's mean acceleration, (v_end - v_start) / T, and the gyro's mean is the offset plus the
// mean yaw rate. When the wheels turn during those samples, both motions are taken from the
// wheels (r w forward, r (w_r - w_l) / c in yaw: slip changes little over a second or two) and
// subtracted. The wheels' forward speed at each end is the mean over a tenth of the interval, so
// encoder noise does not enter twice. A moving start leaves the offsets less certain than a rest:
// init_sd() says by how much (0.1 m/s^2 and a tenth of the removed acceleration, a fifth of the
// removed yaw rate, all of it for a skid-steer), and the filter opens its bias states by that.
// Samples before the wheels' first reading count neither as rest nor in a moving start's
// means; with fewer than 10 read, the accelerometer offset starts at zero. A compensated
// accelerometer offset above 0.3 m/s^2 says the slip changed (a hold-back at the start): it starts
// at zero, with that sd.
//
// "At rest" is known late at both ends: the encoders read still (below the filter's threshold,
// which their quantization sets) while the body already creeps off, so the first samples of a
// start carry its acceleration (0.1-0.3 m/s^2 for a tenth of a second moved c_ax by 0.015 m/s^2
// on a simulated ward21 run, which the accelerometer-driven velocity then integrated into a 10
// cm/s drift). An at-rest sample therefore enters the EMA only once the robot has stayed at rest
// for rest_guard_s after it; the samples still waiting when motion is seen are dropped.
#pragma once

#include <array>
#include <cmath>
#include <deque>
#include <vector>

#include "solvers/ema.h"

namespace slipgraph {

// What the wheels say about the body's motion at an IMU sample (the latest encoder reading):
// forward speed r (w_l + w_r) / 2, yaw rate r (w_r - w_l) / c, and whether both read still.
// NaN speeds: no reading yet (not known to be at rest, and left out of a moving start's means).
struct WheelMotion {
  double speed_mps = std::nan("");
  double yaw_rate_radps = std::nan("");
  bool still = true;
};

class ImuOffsetEstimator {
 public:
  // yaw_rate_relative_sd: how far the wheels' yaw rate r (w_r - w_l) / c may be off the body's
  // (0.2; a skid-steer's is off by its effective track, about 1).
  ImuOffsetEstimator(int init_samples, double ema_samples, double rest_guard_s = 0.0,
                     double yaw_rate_relative_sd = 0.2);

  // One IMU sample at time t; gravity_along_x is g sin(phi) (phi uphill positive) at the sample;
  // at_rest says whether the robot is known to be stopped; wheels: the encoders' view of the
  // motion, used while the offsets are being initialised.
  void Add(double t, double accel_x_mps2, double gyro_z_radps, double gravity_along_x_mps2,
           bool at_rest, const WheelMotion& wheels = {});

  bool ready() const { return count_ >= init_samples_; }
  double accel_x_mps2() const { return accel_.value(); }
  double gyro_z_radps() const { return gyro_.value(); }
  // True when the wheels turned before a rest long enough (the offsets are motion-compensated).
  bool moving_start() const { return moving_start_; }
  // A moving start whose compensated accelerometer offset was implausibly large (the slip changed
  // during the initial samples): the offset starts at zero instead.
  bool implausible_start() const { return implausible_; }
  // The initial offsets' extra uncertainty from a moving start, [accel m/s^2, gyro rad/s]; zero
  // after a rest start.
  const std::array<double, 2>& init_sd() const { return init_sd_; }

 private:
  struct Pending {
    double t, accel_offset, gyro_z;
  };
  struct InitSample {
    double t, accel_offset, gyro_z;
    WheelMotion wheels;
  };
  void FinishInitialisation();
  void FinishAtRest(size_t end);  // the wheel-read samples before init_[end]

  int init_samples_;
  double rest_guard_s_;
  double yaw_rate_relative_sd_;
  int count_ = 0;
  std::vector<InitSample> init_;
  bool moving_start_ = false;
  bool implausible_ = false;
  std::array<double, 2> init_sd_{0.0, 0.0};
  ExponentialMovingAverage accel_, gyro_;
  std::deque<Pending> pending_;  // at-rest samples younger than rest_guard_s
};

}  // namespace slipgraph
