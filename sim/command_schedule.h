// The commanded body velocity over time: at rest for rest_start_s, then each CommandSegment in
// turn, ramped at the actuation limits. Shared by the vehicle simulators.
#pragma once

#include <algorithm>
#include <cmath>

#include "sim/scenario.h"

namespace slipgraph {
namespace sim {

class CommandSchedule {
 public:
  explicit CommandSchedule(const Scenario& scenario) : scenario_(scenario) {}

  // Advances the ramped command to time t (call once per step of length dt).
  void Step(double t, double dt) {
    double target_v = 0.0, target_w = 0.0;
    double segment_end = scenario_.rest_start_s;
    if (t >= scenario_.rest_start_s) {
      for (const CommandSegment& segment : scenario_.commands) {
        segment_end += segment.duration_s;
        if (t < segment_end) {
          target_v = segment.v_mps, target_w = segment.yaw_rate_radps;
          break;
        }
      }
    }
    const Actuation& a = scenario_.actuation;
    v_mps_ += std::clamp(target_v - v_mps_, -a.accel_limit_mps2 * dt, a.accel_limit_mps2 * dt);
    yaw_rate_radps_ += std::clamp(target_w - yaw_rate_radps_, -a.yaw_accel_limit_radps2 * dt,
                                  a.yaw_accel_limit_radps2 * dt);
  }

  double v_mps() const { return v_mps_; }
  double yaw_rate_radps() const { return yaw_rate_radps_; }

 private:
  const Scenario& scenario_;
  double v_mps_ = 0.0;
  double yaw_rate_radps_ = 0.0;
};

}  // namespace sim
}  // namespace slipgraph
