// Scores an estimate file against a log's truth.csv and events.csv (`slipgraph evaluate`), the
// yardstick of every estimator: velocity and disturbance RMSE, immobilizations detected or
// missed with their detection delays, and the fraction of samples falsely flagged immobilized.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/estimate_file.h"

namespace slipgraph {

struct EvaluationOptions {
  // An event is detected by the first flagged sample in [t_start - early, t_end], its delay that
  // sample's time less t_start: truth marks the event from the moment the body is still, while
  // slip is already near 1 a moment before. A flag raised earlier and still up then detects it
  // at a delay of -early.
  double detection_early_s = 0.5;
  // Flags within these margins around an event are transition, not false alarms: the slip is
  // near 1 a moment before the body stops, and the EMA needs a moment to fall after the robot is
  // released. Flags before t_start - false_grace_before_s are false alarms.
  double false_grace_before_s = 0.5;
  double false_grace_after_s = 0.5;
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};

struct EventScore {
  double t_start = 0.0;
  double t_end = 0.0;
  bool detected = false;
  double delay_s = 0.0;  // first flag minus t_start (negative: flagged before full stop)
};

struct Evaluation {
  std::string name;
  size_t samples = 0;
  double velocity_rmse = 0.0;     // v_bx vs truth vx, m/s
  double disturbance_rmse = 0.0;  // a_dist vs truth a_dist, m/s^2 (NaN without truth a_dist)
  std::vector<EventScore> events;
  long false_immobilized_samples = 0;
  // Consistency of v_bx (when the estimates carry sd_v_bx): normalized estimation error squared
  // e^2 / sd^2, and the share of samples inside its 95 % bound (chi-square, 1 dof: 3.84).
  double velocity_mean_nees = std::nan("");
  size_t nees_samples = 0, nees_within_95 = 0;
  double nees_sum = 0.0;
  // Sums for combining a suite.
  double velocity_sq_sum = 0.0, disturbance_sq_sum = 0.0;
  size_t disturbance_samples = 0;

  int detected() const;
  double mean_detection_delay_s() const;  // over detected events (NaN when none)
  double false_immobilized_fraction() const;
  double nees_within_95_fraction() const;  // NaN without sd_v_bx
};

// Throws InputError when the estimates lack t, v_bx or immobilized, or the log has no truth.
Evaluation Evaluate(const DriveLog& log, const NumericTable& estimates,
                    const EvaluationOptions& options = {});
// Totals over a suite (RMSE over all samples, events pooled).
Evaluation Combine(const std::vector<Evaluation>& runs, const std::string& name);

nlohmann::json ToJson(const Evaluation& evaluation);
// One line: name, samples, RMSEs, detections, delay, false alarms, v_bx consistency.
void PrintEvaluation(const Evaluation& evaluation, std::ostream& out);

}  // namespace slipgraph
