// The estimate of the Ward & Iagnemma state at one time: what every Ward estimator produces (the
// EKF, the bank of filters, the batch and window smoothers) and what the problem builders
// (problems/) start from. It lives below both, so that the builders never include a solver.
#pragma once

#include <array>

#include "factors/ward_state.h"

namespace slipgraph {

// The slip and immobilization verdict at one estimate (solvers/immobilization_detector.h).
struct SlipEstimate {
  double slip_left = 0.0;  // slip ratio of the left driven wheel/side (factors/slip_ratio.h)
  double slip_right = 0.0;
  double slip_ema = 0.0;   // EMA of the mean of the two
  double threshold = 0.0;  // the speed-dependent threshold in force
  bool braking = false;
  bool immobilized = false;
};

struct WardEstimate {
  double t = 0.0;
  std::array<double, ward::kStateSize> x{};
  std::array<double, ward::kStateSize> sd{};
  SlipEstimate slip;
  double accel_offset_mps2 = 0.0;  // c_ax
  double gyro_offset_radps = 0.0;  // c_gz
  bool offsets_ready = false;
};

// The accelerometer's whole bias c_ax + b_ax over an interval ending at t, as a front end's
// wheels' check measured it (solvers/slip_persistence.h): where the wheels' rim speed held, the
// velocity changed as the rim speed did at the slip the interval opened with, and what the
// accelerometer felt beyond that is its bias (with the gravity an attitude error leaves in it).
// The smoothers take it as a factor (problems/ward_factor_source.h).
struct AccelBiasMeasurement {
  double t = 0.0;
  double bias_mps2 = 0.0;
  double sd_mps2 = 0.0;
};

}  // namespace slipgraph
