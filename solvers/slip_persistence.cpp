#include "solvers/slip_persistence.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slipgraph {
namespace {

// An interval a microsecond short of T closes: stamps summed from a period fall just short of a
// multiple of it.
constexpr double kIntervalToleranceS = 1e-6;
// The speed ratio v0 / w0 within what one less a slip can be: a body faster than its wheels by
// half, or moving against them by half.
constexpr double kMinSpeedRatio = -0.5, kMaxSpeedRatio = 1.5;

}  // namespace

SlipPersistence::SlipPersistence(const SlipPersistenceConfig& config) : config_(config) {
  std::string error;
  if (!config.IsValid(&error)) throw std::invalid_argument(error);
}

void SlipPersistence::ResetRun() {
  left_out_run_ = 0;
  left_out_sign_ = 0.0;
  run_velocity_error_mps_ = 0.0;
  run_unapplied_ = 0;
}

bool SlipPersistence::CountLeftOut(double innovation_mps2, double span_s, bool may_start) {
  const double sign = innovation_mps2 > 0.0 ? 1.0 : (innovation_mps2 < 0.0 ? -1.0 : 0.0);
  const bool continues = left_out_run_ > 0 && sign != 0.0 && sign == left_out_sign_;
  const bool counts = sign != 0.0 && std::abs(innovation_mps2) <= config_.max_lasting_error_mps2 &&
                      (continues || may_start);
  if (!counts || !continues) ResetRun();
  if (!counts) return false;
  ++left_out_run_;
  left_out_sign_ = sign;
  // Over this interval the error moved the prediction's velocity by nu T from the check's.
  run_velocity_error_mps_ += innovation_mps2 * span_s;
  ++run_unapplied_;
  return config_.lasting_intervals > 0 && left_out_run_ >= config_.lasting_intervals;
}

SlipPersistence::Outcome SlipPersistence::Cycle(const CycleInput& in, Measurement* measurement) {
  if (!enabled()) return Outcome::kNone;
  const double t_s = in.t_s, rim_speed_mps = in.rim_speed_mps;
  if (!smoothing_started_) {
    felt_smoothed_mps_ = felt_v_mps_;
    removed_smoothed_mps_ = removed_v_mps_;
    rim_smoothed_mps_ = rim_speed_mps;
    smoothing_started_ = true;
  } else {
    const double dt = std::max(0.0, t_s - last_t_s_);
    const double weight = 1.0 - std::exp(-dt / config_.smoothing_s);
    felt_smoothed_mps_ += weight * (felt_v_mps_ - felt_smoothed_mps_);
    removed_smoothed_mps_ += weight * (removed_v_mps_ - removed_smoothed_mps_);
    rim_smoothed_mps_ += weight * (rim_speed_mps - rim_smoothed_mps_);
  }
  last_t_s_ = t_s;
  const double min_rim_mps = config_.min_rim_speed_mps;
  Outcome outcome = Outcome::kNone;
  if (open_ && t_s - open_t_s_ >= config_.interval_s - kIntervalToleranceS) {
    open_ = false;
    const bool after_left_out = after_left_out_, after_force = after_force_;
    after_left_out_ = after_force_ = false;
    const double span_s = t_s - open_t_s_;
    const double rim_change_mps = rim_smoothed_mps_ - open_rim_smoothed_mps_;
    if (std::abs(rim_smoothed_mps_) > min_rim_mps &&
        rim_smoothed_mps_ * open_rim_smoothed_mps_ > 0.0 && std::abs(open_rim_mps_) > min_rim_mps &&
        std::abs(rim_change_mps) <= config_.max_rim_acceleration_mps2 * span_s) {
      // One less the slip the interval opened with.
      const double speed_ratio =
          std::clamp(open_v_bx_mps_ / open_rim_mps_, kMinSpeedRatio, kMaxSpeedRatio);
      const double felt_change_mps = felt_smoothed_mps_ - open_felt_smoothed_mps_;
      measurement->innovation_mps2 = (felt_change_mps - speed_ratio * rim_change_mps) / span_s;
      const double sd_mps2 = config_.sd_mps / span_s;
      measurement->variance_mps2_sq = sd_mps2 * sd_mps2;
      measurement->removed_bias_mps2 =
          (removed_smoothed_mps_ - open_removed_smoothed_mps_) / span_s;
      const double nu = measurement->innovation_mps2;
      const double predicted = in.bias_variance_mps2_sq + measurement->variance_mps2_sq;
      const double gate = config_.gate_sd;
      const bool gated = nu * nu > gate * gate * predicted;
      const bool left_out = gated || after_left_out;
      // A tail continues a run only while it reads an error beyond the measurement's own sd (a
      // growing bias variance may have let it back inside the gate); the tail of a force beyond
      // a bias error continues none and starts none.
      const bool reads_error = gated || nu * nu > gate * gate * measurement->variance_mps2_sq;
      if (!left_out || !reads_error) ResetRun();
      const bool lasting = left_out && reads_error && CountLeftOut(nu, span_s, !after_force);
      outcome = left_out && !lasting ? Outcome::kLeftOut : Outcome::kMeasured;
      after_left_out_ = gated && !lasting;  // the next interval holds the force's smoothed tail
      after_force_ = gated && std::abs(nu) > config_.max_lasting_error_mps2;
      if (lasting) {
        measurement->velocity_innovation_mps = -run_velocity_error_mps_;
        measurement->velocity_variance_mps_sq = run_unapplied_ * config_.sd_mps * config_.sd_mps;
        run_velocity_error_mps_ = 0.0;
        run_unapplied_ = 0;
      }
    } else {
      ResetRun();
    }
  }
  if (!open_ && std::abs(rim_smoothed_mps_) > min_rim_mps) {
    open_ = true;
    open_t_s_ = t_s;
    open_felt_smoothed_mps_ = felt_smoothed_mps_;
    open_removed_smoothed_mps_ = removed_smoothed_mps_;
    open_rim_smoothed_mps_ = rim_smoothed_mps_;
    open_rim_mps_ = rim_speed_mps;
    open_v_bx_mps_ = in.v_bx_mps;
  }
  return outcome;
}

}  // namespace slipgraph
