// How far the attitude stream's yaw is from the direction GNSS says the robot moves, tracked
// over the drive, so that a GNSS velocity is projected on the body's heading (eq. 11's
// measurement, factors/frames.h GnssVelocityAlongBodyX) even where an AHRS's yaw has its own
// reference: a magnetometer near steel, an orientation integrated from the gyro, a yaw offset
// in an import mapping that holds on part of the drive only. A heading off by e reads the
// speed as speed cos(e), and the filter's velocity follows it below the robot's.
//
// Each fix whose horizontal speed is well above its noise, while the wheels drive one way,
// gives the course minus the yaw (plus pi when the wheels drive backwards); the offset is the
// circular mean of those, weighted as an exponential moving average over `fixes` fixes, and its
// sd the scatter over the number of fixes the average spans. It is applied only where it is
// both larger than `min_offset_rad` and 3 sd from zero: a yaw within a few degrees of the
// course (every simulated suite) is left as it is, and one fix never moves the heading.
// The estimate at a fix is from the fixes before it, never the fix itself.
#pragma once

#include <algorithm>
#include <cmath>

namespace slipgraph {

struct GnssHeadingOffsetOptions {
  double fixes = 20.0;           // span of the moving average, fixes
  double min_speed_in_sd = 2.5;  // a fix counts above this many of its velocity sd ...
  double min_speed_mps = 0.3;    // ... and above this speed
  double min_drive_radps = 0.5;  // the wheels' mean speed that gives the drive's direction
  int min_fixes = 5;             // fixes before an offset may apply
  double min_offset_rad = 0.05;  // smaller offsets are left out (3 degrees)
};

class GnssHeadingOffset {
 public:
  explicit GnssHeadingOffset(const GnssHeadingOffsetOptions& options = {}) : options_(options) {}

  // One fix: velocity east and north (m/s) with its sd, the attitude's yaw (rad, REP-103) and
  // the wheels' mean angular speed (rad/s, its sign the drive's direction). Returns whether the
  // fix was counted.
  bool Observe(double ve, double vn, double sd_v, double yaw_rad, double wheel_mean_radps) {
    const double speed = std::hypot(ve, vn);
    if (!std::isfinite(speed) || !std::isfinite(yaw_rad) || !std::isfinite(wheel_mean_radps) ||
        std::abs(wheel_mean_radps) < options_.min_drive_radps ||
        speed < std::max(options_.min_speed_mps, options_.min_speed_in_sd * sd_v)) {
      return false;
    }
    const double backwards = wheel_mean_radps < 0.0 ? M_PI : 0.0;
    const double d = std::remainder(std::atan2(vn, ve) - yaw_rad - backwards, 2.0 * M_PI);
    ++count_;
    const double w = std::max(2.0 / (1.0 + options_.fixes), 1.0 / count_);
    cos_ += w * (std::cos(d) - cos_);
    sin_ += w * (std::sin(d) - sin_);
    const double mean = std::atan2(sin_, cos_);
    const double deviation = std::remainder(d - mean, 2.0 * M_PI);
    scatter_sq_ += w * (deviation * deviation - scatter_sq_);
    return true;
  }

  // The mean course minus yaw (rad), 0 before the first counted fix.
  double mean_rad() const { return count_ > 0 ? std::atan2(sin_, cos_) : 0.0; }
  // Its sd: the fixes' scatter over the number the average spans.
  double sd_rad() const {
    if (count_ < 2) return M_PI;
    const double span = std::min(static_cast<double>(count_), 0.5 * (1.0 + options_.fixes));
    return std::sqrt(scatter_sq_ / span);
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

 private:
  GnssHeadingOffsetOptions options_;
  int count_ = 0;
  double cos_ = 0.0, sin_ = 0.0, scatter_sq_ = 0.0;
};

}  // namespace slipgraph
