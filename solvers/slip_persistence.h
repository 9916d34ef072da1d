// The wheels' check on the accelerometer bias, beyond the paper (ModelConfig::slip_persistence).
//
// Where the accelerometer drives the velocity (docs/ekf.md), an error in the bias b_ax, or in the
// gravity an AHRS's slowly wrong pitch removes, integrates into v_bx; on a slow robot 0.04 m/s^2
// takes a third of a 0.12 m/s speed in a second, and the slip that follows reads as an
// immobilization. Only GNSS (0.1 m/s a fix) and the tire law (whose error is of the same size)
// hold it back. But the slip of a robot on steady ground persists: over an interval T the body's
// speed changes as the wheels' rim speed does, at the slip the interval started with, unless a
// force acts that the accelerometer feels clearly (a hold-back decelerates at 0.6-1.8 m/s^2 for
// a tenth of a second). So
//
//   nu = (dv_felt - (v0 / w0) dw) / T    measures    b_ax(true) - b_ax(estimated)
//
// where dv_felt is the velocity change the prediction integrated from the accelerometer (with
// the bias then estimated), w = r (w_l + w_r) / 2 the rim speed from the filter's wheel-speed
// states, dw its change over the interval, v0 and w0 the filter's velocity and that rim speed
// (not smoothed) when it opened: v0 / w0 is one less the slip. Both changes are taken from the
// same first-order smoothing (a time constant of smoothing_s) of the integrated velocity and the
// rim speed, so that one encoder count's step does not read as an acceleration. The slip's own
// change over an interval is the measurement's noise, sd_mps in velocity (variance (sd_mps / T)^2
// on b_ax). A measurement beyond gate_sd of its predicted sd (the bias's variance plus its own) is
// a force the accelerometer felt, not a bias: it is left out, and so is the next interval's, which
// holds the smoothed tail of the same force; the slip that force made persists from then on.
// Such a force is a pulse. Intervals left out that go on (lasting_intervals in a row, the gated
// and their tails, of one sign, each within max_lasting_error_mps2, a tail beyond gate_sd of its
// own sd) are the bias estimate's error grown past the gate (a growing bias variance may let a
// tail back inside it): from the last of them on each is applied, with the velocity the error
// moved the prediction by over the run's intervals not yet applied, sum(nu T), as a measurement
// of v_bx's error -sum(nu T) (variance sd_mps^2 per interval). Without it the slip the velocity
// ran off to would persist in the check too. The tail of a gated force beyond that bound neither
// continues a run nor starts one.
// An interval opens while the smoothed rim speed is above min_rim_speed_mps, and closes when it is
// T long; it measures only if the rim speed, smoothed at both ends and as given at its opening,
// stayed above that floor on the same side, and if the smoothed rim speed changed by no more than
// max_rim_acceleration_mps2 times T (a stalled wheel that spins up changes its slip on its own).
#pragma once

#include "model/model_config.h"

namespace slipgraph {

class SlipPersistence {
 public:
  // Throws std::invalid_argument when the config is not valid (SlipPersistenceConfig::IsValid).
  explicit SlipPersistence(const SlipPersistenceConfig& config);

  bool enabled() const { return config_.interval_s > 0.0; }
  // The prediction's change of v_bx from the accelerometer (m/s), added to the running integral,
  // and the integral over the step of the bias c_ax + b_ax it removed from the accelerometer
  // (m/s).
  void AddFeltVelocityChange(double dv_mps, double removed_bias_mps) {
    felt_v_mps_ += dv_mps;
    removed_v_mps_ += removed_bias_mps;
  }

  struct Measurement {
    double innovation_mps2 = 0.0;   // on b_ax: b_ax(true) - b_ax(estimated)
    double variance_mps2_sq = 0.0;  // (m/s^2)^2
    // The mean bias c_ax + b_ax the prediction removed over the interval (through the same
    // smoothing): plus the innovation, the whole bias the wheels measured.
    double removed_bias_mps2 = 0.0;
    // Where a lasting error is applied: v_bx(true) - v_bx(estimated) the prediction's error
    // integrated over the run (m/s) and its variance; 0 and 0 otherwise.
    double velocity_innovation_mps = 0.0;
    double velocity_variance_mps_sq = 0.0;
  };
  enum class Outcome { kNone, kMeasured, kLeftOut };
  // One wheel cycle: its time, the rim speed r (w_l + w_r) / 2 of the filter's wheel-speed states,
  // the filter's v_bx and its b_ax variance, before the check's own update.
  struct CycleInput {
    double t_s = 0.0;
    double rim_speed_mps = 0.0;
    double v_bx_mps = 0.0;
    double bias_variance_mps2_sq = 0.0;
  };
  // When an interval closes and qualifies: kMeasured, with *measurement to apply (and, for a
  // lasting error, its velocity_* to apply with it), or kLeftOut (by the gate, or as the tail
  // after one the gate left out; *measurement filled either way).
  Outcome Cycle(const CycleInput& in, Measurement* measurement);

 private:
  // Adds a left-out interval's innovation to the run (one that does not continue it starts a
  // new one where may_start); true when the run is a lasting error.
  bool CountLeftOut(double innovation_mps2, double span_s, bool may_start);
  void ResetRun();

  SlipPersistenceConfig config_;
  double felt_v_mps_ = 0.0;     // the integrated accelerometer velocity (its origin is arbitrary)
  double removed_v_mps_ = 0.0;  // the integrated bias the prediction removed (the same)
  double felt_smoothed_mps_ = 0.0, rim_smoothed_mps_ = 0.0, removed_smoothed_mps_ = 0.0;
  double last_t_s_ = 0.0;
  bool smoothing_started_ = false;
  bool open_ = false;
  bool after_left_out_ = false;  // the previous interval was left out
  bool after_force_ = false;     // ... by the gate, beyond a bias error
  // The intervals left out in a row (gated, or a gated one's tail), their innovations' sign, and
  // the velocity the error moved over those of them not yet applied, sum(nu T), with their count.
  int left_out_run_ = 0;
  double left_out_sign_ = 0.0;
  double run_velocity_error_mps_ = 0.0;
  int run_unapplied_ = 0;
  double open_t_s_ = 0.0, open_felt_smoothed_mps_ = 0.0, open_rim_smoothed_mps_ = 0.0,
         open_removed_smoothed_mps_ = 0.0;
  // The slip the interval opened with, from the filter's v_bx and the rim speed (not smoothed).
  double open_v_bx_mps_ = 0.0, open_rim_mps_ = 0.0;
};

}  // namespace slipgraph
