// How far the attitude stream's yaw is from the direction GNSS says the robot moves, tracked
// over the drive, so that a GNSS velocity is projected on the body's heading (eq. 11's
// measurement, factors/frames.h GnssVelocityAlongBodyX) even where an AHRS's yaw has its own
// reference: a magnetometer near steel, an orientation integrated from the gyro, a yaw offset
// in an import mapping that holds on part of the drive only. A heading off by e reads the
// speed as speed cos(e), and the filter's velocity follows it below the robot's.
//
// A fix counts when its horizontal speed is well above its noise while the encoders say the
// robot drives one way on a nearly straight path (a turn's sideslip and an antenna's lever arm
// move the course off the heading by an angle that grows with the path's curvature). It gives
// the course minus the yaw (plus pi when the wheels drive backwards); the offset is the circular
// mean of those, an exponential moving average over `fixes` fixes, and its sd their scatter (or
// their stated noise, if larger) over the number of fixes the average spans. Once `min_fixes`
// have counted, a fix more than `outlier_rad` from the mean is left out (a multipath fix, a
// slipping turn), and `min_fixes` such fixes in a row start the average again (a yaw whose
// reference jumped). The offset is applied only where it is both larger than `min_offset_rad`
// and 3 sd from zero: a yaw within a few degrees of the course (every simulated suite) is left
// as it is, and one fix never moves the heading. The estimate at a fix is from the fixes before
// it, never the fix itself.
//
// The front end (solvers/ward_ekf.h) feeds it fix by fix; the smoothers' GNSS factors and the
// trust check read the same rule over a whole log (io/gnss_heading_offsets.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "model/option_check.h"

namespace slipgraph {

struct GnssHeadingOffsetOptions {
  double fixes = 20.0;               // span of the moving average, fixes
  double min_speed_in_sd = 2.5;      // a fix counts above this many of its velocity sd ...
  double min_speed_mps = 0.3;        // ... and above this speed,
  double min_wheel_speed_mps = 0.1;  // with the wheels' rim speed above this (the direction),
  double max_curvature_per_m = 0.2;  // and their yaw rate over it below this (radius 5 m),
  double max_wheel_age_s = 0.25;     // from a reading no older than this
  double outlier_rad = 0.5 * M_PI;   // farther from an established mean: left out
  int min_fixes = 5;                 // fixes before an offset may apply
  double min_offset_rad = 0.05;      // smaller offsets are left out (3 degrees)

  bool IsValid(std::string* error) const {
    return OptionCheck("GnssHeadingOffsetOptions", error)
        .AtLeast("fixes", fixes, 1.0)
        .NonNegative("min_speed_in_sd", min_speed_in_sd)
        .NonNegative("min_speed_mps", min_speed_mps)
        .NonNegative("min_wheel_speed_mps", min_wheel_speed_mps)
        .Positive("max_curvature_per_m", max_curvature_per_m)
        .NonNegative("max_wheel_age_s", max_wheel_age_s)
        .Within("outlier_rad", outlier_rad, 0.0, M_PI)
        .AtLeast("min_fixes", min_fixes, 1)
        .NonNegative("min_offset_rad", min_offset_rad);
  }
};

class GnssHeadingOffset {
 public:
  explicit GnssHeadingOffset(const GnssHeadingOffsetOptions& options = {}) : options_(options) {
    std::string error;
    if (!options_.IsValid(&error)) throw std::invalid_argument(error);
  }

  // One fix: velocity east and north (m/s) with its sd, the attitude's yaw (rad, REP-103), and
  // the encoders' forward speed (m/s, r times the sides' mean; its sign the drive's direction)
  // and yaw rate (rad/s, r (w_right - w_left) / track). Returns whether the fix was counted.
  bool Observe(double ve_mps, double vn_mps, double sd_v_mps, double yaw_rad,
               double wheel_speed_mps, double wheel_yaw_rate_radps) {
    const double speed_mps = std::hypot(ve_mps, vn_mps);
    const double wheel_abs_mps = std::abs(wheel_speed_mps);
    if (!std::isfinite(speed_mps) || !std::isfinite(yaw_rad) || !std::isfinite(wheel_abs_mps) ||
        !std::isfinite(wheel_yaw_rate_radps) || wheel_abs_mps < options_.min_wheel_speed_mps ||
        std::abs(wheel_yaw_rate_radps) > options_.max_curvature_per_m * wheel_abs_mps ||
        speed_mps < std::max(options_.min_speed_mps, options_.min_speed_in_sd * sd_v_mps)) {
      return false;
    }
    const double backwards_rad = wheel_speed_mps < 0.0 ? M_PI : 0.0;
    const double d_rad =
        std::remainder(std::atan2(vn_mps, ve_mps) - yaw_rad - backwards_rad, 2.0 * M_PI);
    const double deviation_rad = count_ > 0 ? std::remainder(d_rad - mean_rad(), 2.0 * M_PI) : 0.0;
    if (count_ >= options_.min_fixes && std::abs(deviation_rad) > options_.outlier_rad) {
      if (++outliers_in_row_ < options_.min_fixes) return false;
      count_ = 0;  // the yaw's reference moved: start again from this fix
    }
    outliers_in_row_ = 0;
    ++count_;
    // Weighted incremental mean and variance (West 1979), the deviation from the mean before
    // this fix; the scatter is about the mean, low by the span's one fix that sd_rad() restores.
    const double w = std::max(2.0 / (1.0 + options_.fixes), 1.0 / count_);
    cos_ += w * (std::cos(d_rad) - cos_);
    sin_ += w * (std::sin(d_rad) - sin_);
    scatter_rad2_ = (1.0 - w) * (scatter_rad2_ + w * deviation_rad * deviation_rad);
    const double stated_rad = sd_v_mps / speed_mps;  // the fix's own direction sd
    stated_rad2_ += w * (stated_rad * stated_rad - stated_rad2_);
    return true;
  }

  // The mean course minus yaw (rad), 0 before the first counted fix.
  double mean_rad() const { return count_ > 0 ? std::atan2(sin_, cos_) : 0.0; }
  // Its sd: the fixes' scatter over the number the average spans less one (an average with
  // weight 2 / (1 + fixes) has the variance of a mean of `fixes`; the scatter is about the mean),
  // or their stated direction sd (velocity sd over speed) over that number, whichever is larger:
  // a few fixes that happen to agree do not make the mean surer than their noise allows.
  double sd_rad() const {
    if (count_ < 2) return M_PI;
    const double span = std::min(static_cast<double>(count_), options_.fixes);
    return std::sqrt(std::max(scatter_rad2_ / std::max(1.0, span - 1.0), stated_rad2_ / span));
  }
  // What to add to the attitude's yaw: the mean where it is established (module docs), else 0.
  double offset_rad() const {
    const double mean = mean_rad();
    const bool established = count_ >= options_.min_fixes &&
                             std::abs(mean) > options_.min_offset_rad &&
                             std::abs(mean) > 3.0 * sd_rad();
    return established ? mean : 0.0;
  }
  int fixes_counted() const { return count_; }
  const GnssHeadingOffsetOptions& options() const { return options_; }

 private:
  GnssHeadingOffsetOptions options_;
  int count_ = 0;  // fixes in the average since it (re)started
  int outliers_in_row_ = 0;
  double cos_ = 0.0, sin_ = 0.0, scatter_rad2_ = 0.0, stated_rad2_ = 0.0;
};

}  // namespace slipgraph
