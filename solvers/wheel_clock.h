// How late the encoders' stamps are against the IMU's, from the yaw channel (`slipgraph identify`;
// the model file's calibration.wheels_time_offset). The sides' speed difference r (w_r - w_l)
// follows the yaw gyro in shape (its scale is the effective track), whatever the tire law: so
// the lag that lines the two up is the encoders' delay, be it a clock offset, a driver that
// stamps on receipt, or a controller's odometry averaged over a window (its group delay).
//
// For each candidate lag on a grid, r (w_r - w_l) at each encoder stamp t is regressed on the
// gyro at t - lag (interpolated), with a positive slope (the effective track) and an intercept
// (the gyro's offset) for each log's part of each of `blocks` parts of the drive, every lag on the
// same samples; the lag is the grid's least residual sum of squares, refined by a parabola
// through its neighbours. Its sd is the standard error of the mean of the parts' own readings
// (the residuals are correlated over seconds, so the regression's own sd would be far too small).
//
// The reading is the encoders' delay less the body's yaw response time: the body turns after
// its wheels do (the yaw dynamics of eq. 2; 30-170 ms on the mismatch suite's castor robot,
// whose stamps are exact), which reads as encoders early, and at the rates the drive turns a
// first-order response and a delay cannot be told apart. So only a reading of encoders late is
// taken, where it is `min_sigmas` sd and at least `min_lag_s` above zero: no physics makes the
// gyro lead the wheels. It is then the least delay the stamps have (the response time comes on
// top), and the model takes that. A reading of encoders early is reported, not taken (an IMU
// whose stamps are late is `identify --clock`'s).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

struct WheelClockOptions {
  double max_lag_s = 1.0;          // lags searched: within +- this
  double step_s = 0.01;            // the grid's step (a thousandth of max_lag_s to all of it)
  double max_gap_s = 0.2;          // the gyro is interpolated between samples this close
  int blocks = 8;                  // parts of the drive for the sd (at least 4 must turn enough)
  double min_turn_radps = 0.05;    // a sample turns above this yaw rate ...
  long min_turning_samples = 100;  // ... the drive needs this many such, a part its share
  double min_sigmas = 3.0;         // taken, encoders late, beyond this many sd ...
  double min_lag_s = 0.05;         // ... and this lag

  bool IsValid(std::string* error) const;
};

struct WheelClockReading {
  // How late the encoders are against the gyro, less the body's yaw response time (NaN: too
  // little turning); negative: the gyro follows the wheels.
  double lag_s = std::nan("");
  double sd_s = std::nan("");
  double correlation = std::nan("");  // of r (w_r - w_l) with the gyro at that lag
  double correlation_at_zero = std::nan("");
  long samples = 0;           // encoder samples with the gyro at every lag
  int blocks = 0;             // parts that turned enough
  bool at_grid_edge = false;  // the least residual at +-max_lag_s: a bound, never taken
  bool taken = false;
};

// Over the logs (one robot; each as read, calibrated or not). Throws std::invalid_argument for
// invalid options.
WheelClockReading EstimateWheelClock(const std::vector<DriveLog>& logs,
                                     const WheelClockOptions& options = {});

}  // namespace slipgraph
