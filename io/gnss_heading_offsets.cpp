#include "io/gnss_heading_offsets.h"

#include <cmath>

#include "factors/ward_state.h"
#include "io/measurement_stream.h"

namespace slipgraph {

std::vector<double> GnssHeadingOffsets(const DriveLog& log, const ModelConfig& model,
                                       const GnssHeadingOffsetOptions& options) {
  std::vector<double> offsets(log.gps.size(), 0.0);
  if (!model.gnss_heading_from_course) return offsets;
  const ward::Params params = ward::MakeParams(log.vehicle, model);
  GnssHeadingOffset heading(options);
  size_t a = 0, w = 0;  // the next attitude and encoder samples
  bool have_yaw = false, have_wheels = false;
  double yaw_rad = 0.0, wheels_t_s = 0.0;
  EncoderMotion motion;
  for (size_t i = 0; i < log.gps.size(); ++i) {
    const GpsSample& fix = log.gps[i];
    for (; a < log.attitude.size() && log.attitude[a].t <= fix.t; ++a) {
      const AttitudeSample& s = log.attitude[a];
      if (std::isfinite(s.roll) && std::isfinite(s.pitch) && std::isfinite(s.yaw)) {
        yaw_rad = s.yaw;
        have_yaw = true;
      }
    }
    for (; w < log.wheels.size() && log.wheels[w].t <= fix.t; ++w) {
      const SideSpeeds sides = DrivenSideSpeeds(log.wheels[w], log.vehicle.type);
      if (std::isfinite(sides.left_radps) && std::isfinite(sides.right_radps)) {
        motion = EncoderMotionOf(sides.left_radps, sides.right_radps, params.wheel_radius_m,
                                 params.track_width_m);
        wheels_t_s = log.wheels[w].t;
        have_wheels = true;
      }
    }
    if (!std::isfinite(fix.vx) || !std::isfinite(fix.vy) || !std::isfinite(fix.vz)) continue;
    offsets[i] = heading.offset_rad();
    if (have_yaw && have_wheels && fix.t - wheels_t_s <= options.max_wheel_age_s) {
      heading.Observe(fix.vx, fix.vy, GnssVelocitySd(fix, model.measurement.gps_sd_v_mps), yaw_rad,
                      motion.speed_mps, motion.yaw_rate_radps);
    }
  }
  return offsets;
}

}  // namespace slipgraph
