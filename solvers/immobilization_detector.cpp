#include "solvers/immobilization_detector.h"

#include <algorithm>
#include <cmath>

#include "factors/slip_ratio.h"

namespace slipgraph {

InstantSlip ComputeInstantSlip(const ImmobilizationConfig& config, double wheel_radius_m,
                               double track_width_m, double v_bx, double yaw_rate,
                               double omega_left, double omega_right) {
  InstantSlip out;
  SlipEstimate& e = out.estimate;
  const double surface_left = wheel_radius_m * omega_left;
  const double surface_right = wheel_radius_m * omega_right;
  const double half_track_yaw = 0.5 * track_width_m * yaw_rate;
  e.slip_left = SlipRatio(surface_left, v_bx - half_track_yaw);
  e.slip_right = SlipRatio(surface_right, v_bx + half_track_yaw);
  const double surface = 0.5 * (surface_left + surface_right);
  const double low_speed = std::max(0.0, 1.0 - std::abs(surface) / config.low_speed_mps);
  e.threshold = config.slip_threshold + config.low_speed_threshold_add * low_speed;
  // Braking: the body outruns the wheels (v_bx > r w in the direction of travel).
  e.braking = surface >= 0.0 ? v_bx > surface : v_bx < surface;
  out.wheels_turning = std::abs(surface) > config.min_wheel_speed_mps;
  return out;
}

ImmobilizationDetector::ImmobilizationDetector(const ImmobilizationConfig& config,
                                               double wheel_radius_m, double track_width_m)
    : config_(config),
      wheel_radius_m_(wheel_radius_m),
      track_width_m_(track_width_m),
      ema_(config.ema_samples),
      margin_ema_(config.ema_samples) {}

const SlipEstimate& ImmobilizationDetector::Update(double v_bx, double yaw_rate, double omega_left,
                                                   double omega_right, bool encoders_fresh,
                                                   double v_bx_sd) {
  if (!encoders_fresh) {
    latest_.immobilized = false;
    return latest_;
  }
  const InstantSlip instant = ComputeInstantSlip(config_, wheel_radius_m_, track_width_m_, v_bx,
                                                 yaw_rate, omega_left, omega_right);
  latest_ = instant.estimate;
  latest_.slip_ema = ema_.Add(0.5 * (latest_.slip_left + latest_.slip_right));
  latest_.immobilized =
      instant.wheels_turning && !latest_.braking && latest_.slip_ema > latest_.threshold;
  if (config_.velocity_sd_margin > 0.0) {
    // The velocity moved toward the wheels' surface speed by the margin, not past it.
    const double surface = 0.5 * wheel_radius_m_ * (omega_left + omega_right);
    const double reach = config_.velocity_sd_margin * std::max(0.0, v_bx_sd);
    const double moved = v_bx + std::clamp(surface - v_bx, -reach, reach);
    const InstantSlip margin = ComputeInstantSlip(config_, wheel_radius_m_, track_width_m_, moved,
                                                  yaw_rate, omega_left, omega_right);
    const double margin_ema =
        margin_ema_.Add(0.5 * (margin.estimate.slip_left + margin.estimate.slip_right));
    latest_.immobilized = latest_.immobilized && margin_ema > latest_.threshold;
  }
  return latest_;
}

}  // namespace slipgraph
