#include "evaluation/outage_prediction.h"

#include <algorithm>

namespace slipgraph {
namespace {

// The wheels' mean rim speed over [t_start, t_end] (m/s): the mean over the samples in it of the
// mean of |omega| r over the log's wheels; NaN without a sample in it.
double MeanRimSpeed(const DriveLog& log, double t_start, double t_end) {
  const int wheels = log.wheel_count();
  const auto first =
      std::lower_bound(log.wheels.begin(), log.wheels.end(), t_start,
                       [](const WheelSample& sample, double t) { return sample.t < t; });
  double sum = 0.0;
  long samples = 0;
  for (auto it = first; it != log.wheels.end() && it->t <= t_end; ++it) {
    double speed = 0.0;
    for (int w = 0; w < wheels; ++w) speed += std::abs(it->omega_radps[w]);
    sum += speed / wheels * log.vehicle.wheel_radius_m;
    ++samples;
  }
  return samples > 0 ? sum / samples : std::nan("");
}

// The reference pose's planar position at t, linear between samples; false outside them.
bool PoseAt(const std::vector<PoseSample>& poses, double t, double* x, double* y) {
  const auto after = std::lower_bound(
      poses.begin(), poses.end(), t, [](const PoseSample& pose, double at) { return pose.t < at; });
  if (after == poses.end() || (after == poses.begin() && after->t > t)) return false;
  if (after->t == t || after == poses.begin()) {
    *x = after->x, *y = after->y;
    return true;
  }
  const PoseSample& before = *(after - 1);
  const double w = (t - before.t) / (after->t - before.t);
  *x = before.x + w * (after->x - before.x);
  *y = before.y + w * (after->y - before.y);
  return true;
}

}  // namespace

std::vector<OutageSpan> PlanOutages(const DriveLog& log, const OutagePlanOptions& options) {
  std::vector<OutageSpan> spans;
  if (log.gps.empty() || log.wheel_count() == 0) return spans;
  const std::vector<GpsSample>& fixes = log.gps;
  double next_start = fixes.front().t + options.offset_s;
  size_t a = 0;
  while (true) {
    while (a < fixes.size() && fixes[a].t < next_start) ++a;
    if (a >= fixes.size()) break;
    size_t b = a + 1;
    while (b < fixes.size() && fixes[b].t < fixes[a].t + options.horizon_s) ++b;
    if (b >= fixes.size()) break;
    // A gap in the fixes longer than the span itself is an outage of the log's own, not a span.
    if (fixes[b].t - fixes[a].t <= 1.5 * options.horizon_s &&
        MeanRimSpeed(log, fixes[a].t, fixes[b].t) >= options.min_rim_speed_mps) {
      spans.push_back({a, b, fixes[a].t, fixes[b].t});
    }
    next_start = fixes[b].t + options.recover_s;
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

double PredictionError::rms_m() const {
  if (errors_m.empty()) return std::nan("");
  double sum = 0.0;
  for (const double e : errors_m) sum += e * e;
  return std::sqrt(sum / errors_m.size());
}

double PredictionError::mean_m() const {
  if (errors_m.empty()) return std::nan("");
  double sum = 0.0;
  for (const double e : errors_m) sum += e;
  return sum / errors_m.size();
}

double PredictionError::standard_error_m() const {
  if (errors_m.size() < 2) return std::nan("");
  const double mean = mean_m();
  double sum = 0.0;
  for (const double e : errors_m) sum += (e - mean) * (e - mean);
  return std::sqrt(sum / (errors_m.size() - 1) / errors_m.size());
}

double PredictionError::mean_distance_m() const {
  if (distances_m.empty()) return std::nan("");
  double sum = 0.0;
  for (const double d : distances_m) sum += d;
  return sum / distances_m.size();
}

void AddPredictionErrors(const DriveLog& log, const std::vector<OutageSpan>& spans,
                         const std::vector<WardEstimate>& estimates, PredictionError* error) {
  for (const OutageSpan& span : spans) {
    // The path from the estimate at or just before the span's start to the last one before its
    // end, each estimate held until the next (the filter's own zero-order view between samples).
    auto it =
        std::upper_bound(estimates.begin(), estimates.end(), span.t_start,
                         [](double t, const WardEstimate& estimate) { return t < estimate.t; });
    if (it == estimates.begin() || estimates.empty() || estimates.back().t < span.t_end) continue;
    --it;
    double heading = 0.0, x = 0.0, y = 0.0, t = span.t_start;
    for (; it != estimates.end() && t < span.t_end; ++it) {
      const double next =
          std::min(span.t_end, it + 1 != estimates.end() ? (it + 1)->t : span.t_end);
      const double dt = next - t;
      if (dt <= 0.0) continue;
      const double v = it->x[ward::kVbx], yaw_rate = it->x[ward::kYawRate];
      // The heading at the interval's middle (exact for a constant yaw rate's chord direction to
      // second order).
      const double mid = heading + 0.5 * yaw_rate * dt;
      x += v * std::cos(mid) * dt;
      y += v * std::sin(mid) * dt;
      heading += yaw_rate * dt;
      t = next;
    }
    if (!std::isfinite(x) || !std::isfinite(y)) continue;
    double ax = log.gps[span.first_fix].x, ay = log.gps[span.first_fix].y;
    double bx = log.gps[span.last_fix].x, by = log.gps[span.last_fix].y;
    error->against_pose = !log.pose.empty();
    if (error->against_pose &&
        (!PoseAt(log.pose, span.t_start, &ax, &ay) || !PoseAt(log.pose, span.t_end, &bx, &by))) {
      continue;
    }
    const double reference = std::hypot(bx - ax, by - ay);
    error->errors_m.push_back(std::hypot(x, y) - reference);
    error->distances_m.push_back(reference);
  }
}

}  // namespace slipgraph
