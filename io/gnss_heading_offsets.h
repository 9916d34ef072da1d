// The attitude's yaw against the GNSS course over a whole log (factors/gnss_heading_offset.h),
// fed as the front end feeds it while it streams the log (solvers/ward_ekf.h): at each fix, the
// yaw of the latest attitude sample with finite roll, pitch and yaw and the latest encoder
// reading with both sides finite (no older than the options' max_wheel_age_s), both at or before
// the fix; the log's streams sorted by time, as the front end reads them. The smoothers' GNSS
// factors (problems/ward_factor_source.h) and the trust check's GNSS test (solvers/trust_check.h)
// project each fix on the yaw so corrected.
#pragma once

#include <vector>

#include "factors/gnss_heading_offset.h"
#include "io/drive_log.h"
#include "model/model_config.h"

namespace slipgraph {

// The encoders' forward speed and yaw rate from a reading of the driven sides (rad/s), for a
// wheel radius r and track c: r (w_l + w_r) / 2 and r (w_r - w_l) / c.
struct EncoderMotion {
  double speed_mps = 0.0;
  double yaw_rate_radps = 0.0;
};
inline EncoderMotion EncoderMotionOf(double left_radps, double right_radps, double wheel_radius_m,
                                     double track_width_m) {
  return {0.5 * wheel_radius_m * (left_radps + right_radps),
          wheel_radius_m * (right_radps - left_radps) / track_width_m};
}

// What to add to the attitude's yaw at each of log.gps's fixes (rad; 0 where no offset is
// established), from the fixes before it, with the model's wheel radius, track and stated GNSS
// sd; all zero where ModelConfig::gnss_heading_from_course is off.
std::vector<double> GnssHeadingOffsets(const DriveLog& log, const ModelConfig& model,
                                       const GnssHeadingOffsetOptions& options = {});

}  // namespace slipgraph
