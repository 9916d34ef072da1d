// Whether a run's estimates can be trusted, judged from the log alone (no truth): a model far
// from the robot can leave a filter or a smoother sure of a velocity that every wheel and every
// GNSS fix contradicts, and report convergence and a tight sd around it. Four checks:
//
//   wheels' scale: over consecutive windows of scale_window_s, the samples on the flat (pitch
//     within flat_pitch_rad, when the log has attitude) with both wheels turning one way above
//     min_speed_mps, the mean apparent slip (r w - v) / r w (r w the sides' mean surface speed)
//     below min_mean_slip (the body faster than its wheels turn). A robot runs ahead of its
//     wheels only downhill while braking; seconds of it on the flat say the wheel radius, the
//     twist conversion or the velocity is wrong;
//   flagged while moving: samples flagged immobilized while the GNSS fixes on both sides of
//     them (each within 1.5 s) say the robot moves (ground speed above max(0.3 m/s, 3 sd)), or
//     inside a stretch of flags whose fixes say so together (a slow robot's fix is within its
//     noise of zero, a dozen of them are not): the fixes at least stretch_start_margin_s after
//     the stretch's first flag (a fix averaged over the second before a stop) and
//     stretch_end_margin_s before its last (a flag that outlasts a release), at least
//     stretch_min_fixes of them, whose mean velocity along the body's heading is more than
//     stretch_z_limit of its sd from zero either way (the sd from the fixes' stated sd or their
//     own scatter, the larger); when any of them has no attitude within 1 s, all of them are
//     tested on their squared speed (3-D with a vertical velocity) less its noise's share, more
//     than stretch_z_limit sd above zero (one-sided). Such a stretch's flags are suspect
//     whatever their share; more than moving_flag_fraction of all samples flagged while moving
//     is a detector fooled by its model, and marks every one;
//   wheels: the body-x velocity off both driven sides' surface speeds r w by more than
//     `wheel_scale` x the faster one plus `wheel_margin_mps`, or against both while both turn
//     and the body moves (|v| and |r w| above min_speed_mps): a sample "off the wheels";
//   GNSS: each fix's squared ground speed (3-D when it has a vertical velocity, over k = 3 or 2
//     axes) against the estimate's at the nearest estimate,
//     z = (|g|^2 - k sd_g^2 - v^2) / sqrt(4 v^2 (sd_g^2 + sd_v^2) + 2 k sd_g^4), which is zero-mean
//     with unit variance when the two agree (the k sd_g^2 removes the noise's bias of |g|^2: a
//     noisy fix's speed is never below zero). A velocity that drifts off leaves a run of z of one
//     sign: the run's sum / sqrt(n) above gnss_run_limit, or the mean over any gnss_window fixes
//     above gnss_window_limit, mark the run; the window's estimates are marked.
//
// A run is untrusted when more than suspect_fraction of its samples are off the wheels, more than
// moving_flag_fraction are flagged while GNSS moves, a window fails the wheels' scale check, or
// the GNSS speeds disagree beyond their limits. The marks go to the estimate file (column
// `suspect`).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/state_estimate.h"

namespace slipgraph {

struct TrustOptions {
  double wheel_scale = 1.5;             // |v| above this x the faster side's |r w| ...
  double wheel_margin_mps = 0.3;        // ... plus this: off the wheels
  double min_speed_mps = 0.1;           // the sign check needs body and wheels faster than this
  double suspect_fraction = 0.01;       // more samples off the wheels than this: untrusted
  double gnss_run_limit = 4.0;          // sum z / sqrt(n) over the run
  int gnss_window = 10;                 // fixes
  double gnss_window_limit = 2.0;       // mean z over a window (2 sqrt(10) = 6.3 sd of it)
  int min_gnss_fixes = 5;               // fewer fixes: no GNSS verdict on the run
  double scale_window_s = 5.0;          // the wheels' scale check's window ...
  double min_mean_slip = -0.2;          // ... and its limit on the mean apparent slip
  double flat_pitch_rad = 0.05;         // steeper samples are left out of it (about 3 degrees)
  double moving_flag_fraction = 0.05;   // flagged immobilized while GNSS moves: at most this
  double stretch_z_limit = 3.0;         // a flagged stretch's fixes from zero by this many sd ...
  int stretch_min_fixes = 4;            // ... from at least this many fixes ...
  double stretch_start_margin_s = 1.5;  // ... none within this of its first flag ...
  double stretch_end_margin_s = 1.0;    // ... nor of its last: it moves
  // Whether a stretch's fixes are projected on the yaw corrected by the course, as the
  // estimators project them (the run's ModelConfig::gnss_heading_from_course).
  bool gnss_heading_from_course = true;

  bool IsValid(std::string* error) const;
};

struct TrustReport {
  bool trusted = true;
  std::vector<std::string> warnings;  // one line each, why it is not trusted
  // Per estimate: 1 where it is off the wheels, inside a GNSS window or a window of the wheels'
  // scale that fails, or flagged in a stretch whose fixes say the robot moves (every flag while
  // GNSS moves where their share fails), else 0.
  std::vector<double> suspect;
  double off_wheels_fraction = 0.0;
  // Samples flagged immobilized while GNSS says the robot moves, as a fraction of all samples.
  double flagged_moving_fraction = 0.0;
  // The largest z of a flagged stretch's fixes against a robot at rest (NaN: no stretch had
  // stretch_min_fixes fixes; below zero where the only test was one-sided and found quiet fixes).
  double worst_stretch_z = std::nan("");
  // The lowest mean apparent slip over a window of the wheels' scale check (NaN: no window).
  double lowest_window_slip = std::nan("");
  double gnss_run_z = std::nan("");         // sum z / sqrt(n); NaN without enough fixes
  double gnss_worst_window = std::nan("");  // the largest |mean z| over gnss_window fixes
  size_t gnss_fixes = 0;
};

// Throws std::invalid_argument for invalid options.
TrustReport CheckTrust(const DriveLog& log, const std::vector<WardEstimate>& estimates,
                       const TrustOptions& options = {});

// For the terminal: "trust: ..." with the figures, then one line per warning.
std::string DescribeTrust(const TrustReport& report);

}  // namespace slipgraph
