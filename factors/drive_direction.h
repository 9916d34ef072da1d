// The drive direction of Ward & Iagnemma's Table I (VelDir), the wheel speed below which a
// wheel reads as stopped and how long both have been stopped: the conditions the EKF's weak
// constraints and the smoother's soft priors share.
#pragma once

#include <cmath>

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

// Both driven wheels' speeds below the still threshold (NaN reads as not still).
inline bool BothWheelsStill(double omega_left_radps, double omega_right_radps,
                            double wheel_still_radps) {
  return std::abs(omega_left_radps) < wheel_still_radps &&
         std::abs(omega_right_radps) < wheel_still_radps;
}

// Whether both driven wheels have settled: each wheel's speed, smoothed over a time constant (an
// exponential moving average), below the still threshold. An encoder that sits on the edge of a
// count reads one count now and then while its wheel stands: at 100 Hz and 4096 counts a turn
// that is 0.153 rad/s, just above the threshold. The smoothed speed of a standing wheel stays
// near zero, so such a count does not end the stop; a wheel that starts to turn passes the
// threshold within a fraction of the time constant (WheelRestTimer also reads each reading, so
// that nothing at rest is applied to a cycle whose wheels read as turning). A time constant of 0
// takes each reading as it is (the paper's test).
class WheelStillness {
 public:
  explicit WheelStillness(double time_constant_s = 0.0) : time_constant_s_(time_constant_s) {}
  // Feeds one encoder cycle, in time order. With a time constant of 0 each reading is taken as
  // it is (a reading that is not finite reads as not still); otherwise a reading that is not
  // finite, or not later than the last one, leaves the smoothed speeds as they are.
  void Update(double t, double omega_left_radps, double omega_right_radps) {
    if (!(time_constant_s_ > 0.0) || !started_) {
      left_ = omega_left_radps, right_ = omega_right_radps, t_ = t;
      started_ = std::isfinite(left_) && std::isfinite(right_);
      return;
    }
    if (!std::isfinite(omega_left_radps) || !std::isfinite(omega_right_radps) || !(t > t_)) return;
    const double gain = 1.0 - std::exp(-(t - t_) / time_constant_s_);
    left_ += gain * (omega_left_radps - left_);
    right_ += gain * (omega_right_radps - right_);
    t_ = t;
  }
  bool Still(double wheel_still_radps) const {
    return BothWheelsStill(left_, right_, wheel_still_radps);
  }

 private:
  double time_constant_s_ = 0.0;
  double left_ = 0.0, right_ = 0.0, t_ = 0.0;
  bool started_ = false;
};

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

// Weak constraint 4's at-rest rule: both driven wheels settled (WheelStillness over the model's
// still_smoothing) for the timer's duration, AND this cycle's own reading still, so that nothing
// at rest is applied to a cycle whose wheels read as turning. Fed each encoder cycle in time
// order; a cycle whose reading is not finite is skipped (the rule stands as it was).
class WheelRestTimer {
 public:
  WheelRestTimer(double smoothing_s, double wheel_still_radps)
      : stillness_(smoothing_s), still_radps_(wheel_still_radps) {}
  void Update(double t, double omega_left_radps, double omega_right_radps) {
    if (!std::isfinite(omega_left_radps) || !std::isfinite(omega_right_radps)) return;
    reading_still_ = BothWheelsStill(omega_left_radps, omega_right_radps, still_radps_);
    stillness_.Update(t, omega_left_radps, omega_right_radps);
    settled_.Update(t, stillness_.Still(still_radps_));
  }
  // Both wheels below the still threshold at the latest finite reading.
  bool reading_still() const { return reading_still_; }
  // The rule as a plain timer: the settled one while the latest reading is still, else one that
  // is not running (a smoother keeps this per state).
  WheelStopTimer Timer() const { return reading_still_ ? settled_ : WheelStopTimer(); }
  double StoppedFor(double t) const { return Timer().StoppedFor(t); }
  bool AtRestFor(double t, double duration) const { return Timer().AtRestFor(t, duration); }

 private:
  WheelStillness stillness_;
  WheelStopTimer settled_;
  double still_radps_;
  bool reading_still_ = false;
};

}  // namespace slipgraph
