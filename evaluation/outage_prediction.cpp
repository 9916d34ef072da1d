#include "evaluation/outage_prediction.h"

#include <algorithm>
#include <stdexcept>

#include "io/measurement_stream.h"
#include "model/option_check.h"

namespace slipgraph {

bool OutagePlanOptions::IsValid(std::string* error) const {
  return OptionCheck("OutagePlanOptions", error)
      .Positive("horizon_s", horizon_s)
      .NonNegative("recover_s", recover_s)
      .NonNegative("offset_s", offset_s)
      .NonNegative("min_rim_speed_mps", min_rim_speed_mps)
      .AtLeast("max_span_horizons", max_span_horizons, 1.0)
      .Positive("max_pose_gap_s", max_pose_gap_s)
      .NonNegative("stated_fix_sd_xy_m", stated_fix_sd_xy_m);
}

namespace {

// The driven sides' mean rim speed over [t_start_s, t_end_s] (m/s): the mean over the wheel
// samples in it of the mean of |omega| r over the two sides (DrivenSideSpeeds); NaN without a
// sample in it.
double MeanRimSpeedMps(const DriveLog& log, double t_start_s, double t_end_s) {
  const auto first =
      std::lower_bound(log.wheels.begin(), log.wheels.end(), t_start_s,
                       [](const WheelSample& sample, double t_s) { return sample.t < t_s; });
  double sum_mps = 0.0;
  long samples = 0;
  for (auto it = first; it != log.wheels.end() && it->t <= t_end_s; ++it) {
    const SideSpeeds sides = DrivenSideSpeeds(*it, log.vehicle.type);
    sum_mps += 0.5 * (std::abs(sides.left_radps) + std::abs(sides.right_radps)) *
               log.vehicle.wheel_radius_m;
    ++samples;
  }
  return samples > 0 ? sum_mps / samples : std::nan("");
}

// The mean and the root mean square of `values`, NaN when empty.
double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nan("");
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / values.size();
}
double Rms(const std::vector<double>& values) {
  if (values.empty()) return std::nan("");
  double sum_sq = 0.0;
  for (const double v : values) sum_sq += v * v;
  return std::sqrt(sum_sq / values.size());
}

// The reference pose's planar position at t_s, linear between the samples around it, and its
// stated sd (the larger of x's and y's, NaN where not stated); false outside the samples or where
// they are more than max_gap_s apart.
bool PoseAt(const std::vector<PoseSample>& poses, double t_s, double max_gap_s, double* x_m,
            double* y_m, double* sd_m) {
  const auto after =
      std::lower_bound(poses.begin(), poses.end(), t_s,
                       [](const PoseSample& pose, double at_s) { return pose.t < at_s; });
  if (after == poses.end()) return false;
  *sd_m = std::fmax(after->sd_x, after->sd_y);  // NaN only where neither is stated
  if (after->t == t_s) {
    *x_m = after->x, *y_m = after->y;
    return true;
  }
  if (after == poses.begin()) return false;
  const PoseSample& before = *(after - 1);
  if (after->t - before.t > max_gap_s) return false;
  const double w = (t_s - before.t) / (after->t - before.t);
  *x_m = before.x + w * (after->x - before.x);
  *y_m = before.y + w * (after->y - before.y);
  return true;
}

// A fix's position sd: its row's where stated, else the model's.
double FixSdM(const GpsSample& fix, double stated_m) {
  return std::isfinite(fix.sd_xy) && fix.sd_xy > 0.0 ? fix.sd_xy : stated_m;
}

}  // namespace

std::vector<OutageSpan> PlanOutages(const DriveLog& log, const OutagePlanOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  std::vector<OutageSpan> spans;
  if (log.gps.empty() || log.wheel_count() == 0) return spans;
  const std::vector<GpsSample>& fixes = log.gps;
  double next_start_s = fixes.front().t + options.offset_s;
  size_t a = 0;
  while (true) {
    while (a < fixes.size() && fixes[a].t < next_start_s) ++a;
    if (a >= fixes.size()) break;
    size_t b = a + 1;
    while (b < fixes.size() && fixes[b].t < fixes[a].t + options.horizon_s) ++b;
    if (b >= fixes.size()) break;
    // A gap in the fixes much longer than the span is an outage of the log's own, not a span.
    if (fixes[b].t - fixes[a].t <= options.max_span_horizons * options.horizon_s &&
        MeanRimSpeedMps(log, fixes[a].t, fixes[b].t) >= options.min_rim_speed_mps) {
      spans.push_back({a, b, fixes[a].t, fixes[b].t});
    }
    // The next span starts at fix b or later: spans never overlap, and the loop ends.
    next_start_s = fixes[b].t + options.recover_s;
    a = b;
  }
  return spans;
}

DriveLog WithoutFixesInside(const DriveLog& log, const std::vector<OutageSpan>& spans) {
  DriveLog out = log;
  out.gps.clear();
  size_t span = 0;
  for (size_t i = 0; i < log.gps.size(); ++i) {
    while (span < spans.size() && spans[span].last_fix <= i) ++span;
    const bool inside = span < spans.size() && spans[span].first_fix < i;
    if (!inside) out.gps.push_back(log.gps[i]);
  }
  return out;
}

double PredictionError::rms_m() const { return Rms(errors_m); }

double PredictionError::mean_m() const { return Mean(errors_m); }

double PredictionError::standard_error_m() const {
  if (errors_m.size() < 2) return std::nan("");
  const double mean = mean_m();
  double sum_m2 = 0.0;
  for (const double e_m : errors_m) sum_m2 += (e_m - mean) * (e_m - mean);
  return std::sqrt(sum_m2 / (errors_m.size() - 1) / errors_m.size());
}

double PredictionError::floor_rms_m() const { return Rms(floors_m); }

double PredictionError::mean_distance_m() const { return Mean(distances_m); }

void AddPredictionErrors(const DriveLog& log, const std::vector<OutageSpan>& spans,
                         const std::vector<WardEstimate>& estimates, PredictionError* error,
                         const OutagePlanOptions& options) {
  error->against_pose = !log.pose.empty();
  for (const OutageSpan& span : spans) {
    // The path from the estimate at or just before the span's start to the last one before its
    // end, each estimate held until the next (the filter's own zero-order view between samples).
    const long first = LatestAtOrBefore(estimates, span.t_start_s);
    if (first < 0 || estimates.back().t < span.t_end_s) continue;
    auto it = estimates.begin() + first;
    double heading_rad = 0.0, x_m = 0.0, y_m = 0.0, t_s = span.t_start_s;
    for (; it != estimates.end() && t_s < span.t_end_s; ++it) {
      const double next_s =
          it + 1 != estimates.end() ? std::min(span.t_end_s, (it + 1)->t) : span.t_end_s;
      const double dt_s = next_s - t_s;
      if (dt_s <= 0.0) continue;
      const double v_mps = it->x[ward::kVbx], yaw_rate_radps = it->x[ward::kYawRate];
      // The direction of the interval's chord at a constant yaw rate: the heading at its middle.
      const double chord_rad = heading_rad + 0.5 * yaw_rate_radps * dt_s;
      x_m += v_mps * std::cos(chord_rad) * dt_s;
      y_m += v_mps * std::sin(chord_rad) * dt_s;
      heading_rad += yaw_rate_radps * dt_s;
      t_s = next_s;
    }
    const GpsSample& a = log.gps[span.first_fix];
    const GpsSample& b = log.gps[span.last_fix];
    double ax_m = a.x, ay_m = a.y, bx_m = b.x, by_m = b.y;
    double a_sd_m = FixSdM(a, options.stated_fix_sd_xy_m);
    double b_sd_m = FixSdM(b, options.stated_fix_sd_xy_m);
    if (error->against_pose &&
        (!PoseAt(log.pose, span.t_start_s, options.max_pose_gap_s, &ax_m, &ay_m, &a_sd_m) ||
         !PoseAt(log.pose, span.t_end_s, options.max_pose_gap_s, &bx_m, &by_m, &b_sd_m))) {
      continue;
    }
    const double predicted_m = std::hypot(x_m, y_m);
    const double reference_m = std::hypot(bx_m - ax_m, by_m - ay_m);
    if (!std::isfinite(predicted_m) || !std::isfinite(reference_m)) continue;
    error->errors_m.push_back(predicted_m - reference_m);
    error->distances_m.push_back(reference_m);
    error->floors_m.push_back(std::hypot(a_sd_m, b_sd_m));
  }
}

}  // namespace slipgraph
