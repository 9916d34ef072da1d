// Ward & Iagnemma Sec. III-E: the robot is immobilized when the EMA (eq. 12) of the mean slip of
// the driven wheels exceeds a threshold. The threshold rises at low wheel speed, where encoder
// noise makes slip noisy, and nothing is flagged while braking (v_bx > r w) or when the encoder
// data is stale (missing encoder data is never reported as immobilization).
#pragma once

#include "io/state_estimate.h"
#include "model/model_config.h"
#include "solvers/ema.h"

namespace slipgraph {

// The instantaneous part of the detector, shared with post-processing: the slip of each driven
// side, braking, the speed-dependent threshold, and whether the wheels turn fast enough to count
// as spinning (slip_ema and immobilized are left for the caller).
struct InstantSlip {
  SlipEstimate estimate;
  bool wheels_turning = false;
};
InstantSlip ComputeInstantSlip(const ImmobilizationConfig& config, double wheel_radius_m,
                               double track_width_m, double v_bx_mps, double yaw_rate_radps,
                               double omega_left_radps, double omega_right_radps);

class ImmobilizationDetector {
 public:
  ImmobilizationDetector(const ImmobilizationConfig& config, double wheel_radius_m,
                         double track_width_m);

  // One filter cycle: the estimated v_bx, yaw rate and wheel speeds, and v_bx's sd (for
  // ImmobilizationConfig::velocity_sd_margin). encoders_fresh false (encoder data missing) holds
  // the EMAs and never flags.
  const SlipEstimate& Update(double v_bx_mps, double yaw_rate_radps, double omega_left_radps,
                             double omega_right_radps, bool encoders_fresh,
                             double v_bx_sd_mps = 0.0);
  const SlipEstimate& latest() const { return latest_; }

 private:
  ImmobilizationConfig config_;
  double wheel_radius_m_;
  double track_width_m_;
  ExponentialMovingAverage ema_;
  ExponentialMovingAverage margin_ema_;  // of the slip with the velocity moved by the margin
  SlipEstimate latest_;
};

}  // namespace slipgraph
