#include "solvers/slip_persistence.h"

#include <algorithm>
#include <cmath>

namespace slipgraph {

SlipPersistence::Outcome SlipPersistence::Cycle(double t_s, double rim_speed_mps, double v_bx_mps,
                                                double bias_variance, Measurement* measurement) {
  if (!enabled()) return Outcome::kNone;
  if (!smoothing_started_) {
    felt_smoothed_mps_ = felt_v_mps_;
    rim_smoothed_mps_ = rim_speed_mps;
    smoothing_started_ = true;
  } else {
    const double dt = std::max(0.0, t_s - last_t_s_);
    const double weight = 1.0 - std::exp(-dt / config_.smoothing_s);
    felt_smoothed_mps_ += weight * (felt_v_mps_ - felt_smoothed_mps_);
    rim_smoothed_mps_ += weight * (rim_speed_mps - rim_smoothed_mps_);
  }
  last_t_s_ = t_s;
  const double min_rim = config_.min_rim_speed_mps;
  Outcome outcome = Outcome::kNone;
  // (A microsecond short counts: stamps summed from a period fall just short of a multiple.)
  if (open_ && t_s - open_t_s_ >= config_.interval_s - 1e-6) {
    open_ = false;
    const bool after_left_out = after_left_out_;
    after_left_out_ = false;
    const double span_s = t_s - open_t_s_;
    const double rim_change = rim_smoothed_mps_ - open_rim_mps_;
    if (std::abs(rim_smoothed_mps_) > min_rim && rim_smoothed_mps_ * open_rim_mps_ > 0.0 &&
        std::abs(open_rim_raw_mps_) > min_rim &&
        std::abs(rim_change) <= config_.max_rim_acceleration_mps2 * span_s) {
      // The slip the interval opened with, 1 - v0 / w0, within what a slip can be (a body
      // faster than its wheels by half, or moving against them by half).
      const double keep = std::clamp(open_v_bx_mps_ / open_rim_raw_mps_, -0.5, 1.5);
      const double felt_change = felt_smoothed_mps_ - open_felt_mps_;
      measurement->innovation_mps2 = (felt_change - keep * rim_change) / span_s;
      const double sd_mps2 = config_.sd_mps / span_s;
      measurement->variance = sd_mps2 * sd_mps2;
      const double nu = measurement->innovation_mps2;
      const double predicted = bias_variance + measurement->variance;
      const double gate = config_.gate_sd;
      const bool gated = nu * nu > gate * gate * predicted;
      outcome = gated || after_left_out ? Outcome::kLeftOut : Outcome::kMeasured;
      after_left_out_ = gated;  // the next interval holds the force's smoothed tail
    }
  }
  if (!open_ && std::abs(rim_smoothed_mps_) > min_rim) {
    open_ = true;
    open_t_s_ = t_s;
    open_felt_mps_ = felt_smoothed_mps_;
    open_rim_mps_ = rim_smoothed_mps_;
    open_rim_raw_mps_ = rim_speed_mps;
    open_v_bx_mps_ = v_bx_mps;
  }
  return outcome;
}

}  // namespace slipgraph
