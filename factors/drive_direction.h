// The drive direction of Ward & Iagnemma's Table I (VelDir), the wheel speed below which a
// wheel reads as stopped and how long both have been stopped: the conditions the EKF's weak
// constraints and the smoother's soft priors share.
#pragma once

namespace slipgraph {

// |w| below this reads as a stopped wheel: 3 sd of the LAGR encoder noise at 100 Hz (0.05 rad/s),
// so that noise alone rarely restarts the at-rest timer of weak constraint 4.
constexpr double kDefaultWheelStillRadps = 0.15;

// VelDir of Table I: sign(w_l + w_r), 0 when the sum is within twice the still threshold.
inline double DriveDirection(double omega_left_radps, double omega_right_radps,
                             double wheel_still_radps) {
  const double sum = omega_left_radps + omega_right_radps;
  if (sum > -2.0 * wheel_still_radps && sum < 2.0 * wheel_still_radps) return 0.0;
  return sum > 0.0 ? 1.0 : -1.0;
}

// How long both driven wheels have read still (weak constraint 4's at-rest timer, Table I's
// t_stop): fed each encoder cycle in time order.
class WheelStopTimer {
 public:
  void Update(double t, bool both_still) {
    if (!both_still) {
      stopped_ = false;
    } else if (!stopped_) {
      stopped_ = true;
      since_ = t;
    }
  }
  // Seconds since both wheels first read still in the current stop; 0 while moving.
  double StoppedFor(double t) const { return stopped_ && t > since_ ? t - since_ : 0.0; }
  // Stopped for at least `duration` (never while moving, even for a duration of 0).
  bool AtRestFor(double t, double duration) const { return stopped_ && t - since_ >= duration; }

 private:
  bool stopped_ = false;
  double since_ = 0.0;
};

}  // namespace slipgraph
