// The 2-s prediction error: how far a model's prediction from the wheels and the IMU alone lands
// from where GNSS says the robot went, where no truth exists (Rogers-Marcovitz, Seegmiller &
// Kelly score a slip model by the pose error it predicts over path segments of a few seconds).
//
// The front end runs on the log with GNSS withheld over spans between two fixes (PlanOutages,
// WithoutFixesInside): across a span its estimate is the model's prediction from the state it had
// at the span's first fix. The distance the prediction covers over the span, the chord of the path
// integrated from v_bx and the yaw rate, is compared with the distance between the span's two
// fixes (AddPredictionErrors), or between the reference poses at their times where the log has
// pose.csv (an INS/GNSS solution, as the paper scored against). The chord does not depend on the
// heading at the start, which the model does not predict and a robot's attitude stream may not
// reference to east.
//
// What it measures: the along-path error of the velocity the model gives the wheels (slip, the
// radius, the tire law) and, at second order, the yaw rate's. Against fixes its floor is their
// own position noise (sqrt(2) sd_xy in each chord: 0.7 m for 0.5 m fixes, a third of the distance
// at 1 m/s), the same for every model run on the log: compare models on one log, by the mean
// error (a model's bias, whose standard error falls with the number of spans) as well as the
// RMS.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/state_estimate.h"

namespace slipgraph {

struct OutageSpan {
  size_t first_fix = 0, last_fix = 0;     // indices into log.gps: the fixes at the span's ends
  double t_start_s = 0.0, t_end_s = 0.0;  // their times
};

struct OutagePlanOptions {
  double horizon_s = 2.0;  // a span ends at the first fix at least this long after its start
  // Fixes left between one span and the next, for the filter to recover (s).
  double recover_s = 2.0;
  double offset_s = 0.0;  // the first span starts at the first fix this long after the first fix
  // A span counts where the wheels' mean rim speed over it is at least this (m/s): standing
  // still, every model predicts the robot stands still.
  double min_rim_speed_mps = 0.2;
  // A span whose fixes are further apart than this many horizons spans a gap in the log's own
  // fixes and is not taken.
  double max_span_horizons = 1.5;
  // A reference pose between two samples further apart than this is not interpolated (s).
  double max_pose_gap_s = 1.0;
  // A fix's position sd where its row states none (m): the model's (SensorNoise::gps_sd_xy_m).
  double stated_fix_sd_xy_m = 0.5;
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};

// Spans from fix to fix, each horizon_s long or a little more, recover_s apart, over the whole
// log, and only where the wheels turn (options.min_rim_speed_mps, from the log's wheel samples
// and vehicle.yaml's radius: plan on the log as read, so that every model's run on it is scored
// on the same spans). In time order, not overlapping; empty without fixes. Throws
// std::invalid_argument on options that are not valid.
std::vector<OutageSpan> PlanOutages(const DriveLog& log, const OutagePlanOptions& options = {});

// The log without the fixes strictly inside the spans (the fixes at their ends kept); spans as
// PlanOutages gives them (in time order, not overlapping).
DriveLog WithoutFixesInside(const DriveLog& log, const std::vector<OutageSpan>& spans);

struct PredictionError {
  // Per span: the predicted chord minus the GNSS chord (m); positive: the model ran ahead.
  std::vector<double> errors_m;
  std::vector<double> distances_m;  // the reference's chords (m)
  // Per span: the sd the reference's own noise puts in its chord, sqrt(sd_a^2 + sd_b^2) of the
  // positions at its ends (m; NaN for poses that state no sd).
  std::vector<double> floors_m;

  bool against_pose = false;  // the reference poses (pose.csv) rather than the fixes

  long spans() const { return static_cast<long>(errors_m.size()); }
  double rms_m() const;             // NaN without spans
  double mean_m() const;            // the signed mean, NaN without spans
  double standard_error_m() const;  // the mean's, NaN with fewer than two spans
  double mean_distance_m() const;   // NaN without spans
  // The RMS the reference's stated noise alone would give, were its errors independent from one
  // end of a span to the other (m): a model whose RMS is near it predicts as well as this
  // reference can tell. A receiver whose errors are correlated over 2 s, or whose stated sd is
  // generous, gives less. NaN without spans or where an end's sd is not known.
  double floor_rms_m() const;
};

// Adds one span's error per span (estimates: the front end's on the log WithoutFixesInside the
// spans, in time order), against the log's reference poses where it has them, else its fixes.
// A span whose estimates or poses do not cover it, or whose values are not finite, is left out.
void AddPredictionErrors(const DriveLog& log, const std::vector<OutageSpan>& spans,
                         const std::vector<WardEstimate>& estimates, PredictionError* error,
                         const OutagePlanOptions& options = {});

}  // namespace slipgraph
