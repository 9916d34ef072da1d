#include "evaluation/evaluation.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <stdexcept>

#include "evaluation/json_number.h"
#include "io/csv_writer.h"
#include "io/input_error.h"
#include "model/option_check.h"

namespace slipgraph {

bool EvaluationOptions::IsValid(std::string* error) const {
  return OptionCheck("EvaluationOptions", error)
      .NonNegative("detection_early_s", detection_early_s)
      .NonNegative("false_grace_before_s", false_grace_before_s)
      .NonNegative("false_grace_after_s", false_grace_after_s);
}
namespace {

constexpr double kChiSquare95OneDof = 3.841;

// How far an estimate's time may lie outside the truth's span (a wheel sample after the last
// truth row).
constexpr double kTruthSpanToleranceS = 0.5;

// Truth interpolated linearly in time (truth is dense; clamps at the ends).
class TruthTrack {
 public:
  explicit TruthTrack(const std::vector<TruthSample>& truth) : truth_(truth) {}
  template <typename Field>
  double At(double t, Field field) const {
    auto it = std::lower_bound(truth_.begin(), truth_.end(), t,
                               [](const TruthSample& s, double value) { return s.t < value; });
    if (it == truth_.begin()) return field(truth_.front());
    if (it == truth_.end()) return field(truth_.back());
    const TruthSample& b = *it;
    const TruthSample& a = *(it - 1);
    const double u = (t - a.t) / (b.t - a.t);
    return (1.0 - u) * field(a) + u * field(b);
  }

 private:
  const std::vector<TruthSample>& truth_;
};

const std::vector<double>& Column(const NumericTable& table, const std::string& name) {
  const auto it = table.columns.find(name);
  if (it == table.columns.end()) {
    throw InputError("estimates", 1, name, "", "required column is missing");
  }
  return it->second;
}

}  // namespace

int Evaluation::detected() const {
  return static_cast<int>(
      std::count_if(events.begin(), events.end(), [](const EventScore& e) { return e.detected; }));
}

double Evaluation::mean_detection_delay_s() const {
  double sum = 0.0;
  int n = 0;
  for (const EventScore& e : events) {
    if (e.detected) sum += e.delay_s, ++n;
  }
  return n > 0 ? sum / n : std::nan("");
}

double Evaluation::nees_within_95_fraction() const {
  return nees_samples > 0 ? static_cast<double>(nees_within_95) / nees_samples : std::nan("");
}

double Evaluation::false_immobilized_fraction() const {
  return samples > 0 ? static_cast<double>(false_immobilized_samples) / samples : 0.0;
}

Evaluation Evaluate(const DriveLog& log, const NumericTable& estimates,
                    const EvaluationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  if (log.truth.empty()) {
    throw InputError(log.directory + "/truth.csv", 0, "", "", "evaluation needs truth.csv");
  }
  Evaluation ev;
  ev.name = log.directory;
  const std::vector<double>& t = Column(estimates, "t");
  const std::vector<double>& v = Column(estimates, "v_bx");
  const std::vector<double>& flag = Column(estimates, "immobilized");
  const auto sd_v_it = estimates.columns.find("sd_v_bx");
  const std::vector<double>* sd_v = sd_v_it == estimates.columns.end() ? nullptr : &sd_v_it->second;
  const auto a_dist_it = estimates.columns.find("a_dist");
  const std::vector<double>* a_dist =
      a_dist_it == estimates.columns.end() ? nullptr : &a_dist_it->second;
  const std::string source = estimates.path.empty() ? "estimates" : estimates.path;
  for (const auto& [name, column] : estimates.columns) {
    if (column.size() != t.size()) {  // a table built in memory (a file's columns are equal)
      throw InputError(source, 0, name, std::to_string(column.size()) + " values",
                       "not one per time stamp (" + std::to_string(t.size()) + ")");
    }
  }
  const TruthTrack truth(log.truth);
  std::vector<Event> immobilized;
  for (const Event& e : log.events) {
    if (e.label == "immobilized") immobilized.push_back(e);
  }
  for (const Event& e : immobilized) ev.events.push_back({e.t_start, e.t_end, false, 0.0});

  // Estimates off the truth's time span were scored against its end values: a file of another
  // log, or one on another clock (shifted by 1000 s), scored as if it were this log's.
  const double first_t = log.truth.front().t - kTruthSpanToleranceS;
  const double last_t = log.truth.back().t + kTruthSpanToleranceS;
  for (size_t i = 0; i < t.size(); ++i) {
    const int line = static_cast<int>(i) + 2;  // the header is line 1
    if (!(t[i] >= first_t && t[i] <= last_t)) {
      throw InputError(source, line, "t", FormatNumber(t[i]),
                       "outside truth.csv's time span (" + FormatNumber(log.truth.front().t) +
                           " to " + FormatNumber(log.truth.back().t) +
                           " s): another log's estimates, or another clock");
    }
    if (!std::isfinite(v[i])) {
      throw InputError(source, line, "v_bx", FormatNumber(v[i]), "not a finite estimate");
    }
    ++ev.samples;
    const double dv = v[i] - truth.At(t[i], [](const TruthSample& s) { return s.vx; });
    ev.velocity_sq_sum += dv * dv;
    if (sd_v != nullptr && (*sd_v)[i] > 0.0) {
      const double nees = dv * dv / ((*sd_v)[i] * (*sd_v)[i]);
      ev.nees_sum += nees;
      ++ev.nees_samples;
      if (nees <= kChiSquare95OneDof) ++ev.nees_within_95;
    }
    if (a_dist != nullptr && std::isfinite(log.truth.front().a_dist)) {
      const double da =
          (*a_dist)[i] - truth.At(t[i], [](const TruthSample& s) { return s.a_dist; });
      if (std::isfinite(da)) ev.disturbance_sq_sum += da * da, ++ev.disturbance_samples;
    }
    if (flag[i] < 0.5) continue;
    bool near_event = false;
    for (EventScore& e : ev.events) {
      if (t[i] >= e.t_start - options.detection_early_s && t[i] <= e.t_end && !e.detected) {
        e.detected = true;
        e.delay_s = t[i] - e.t_start;
      }
      near_event = near_event || (t[i] >= e.t_start - options.false_grace_before_s &&
                                  t[i] <= e.t_end + options.false_grace_after_s);
    }
    const double truth_flag = truth.At(t[i], [](const TruthSample& s) {
      return std::isfinite(s.immobilized) ? s.immobilized : 0.0;
    });
    if (!near_event && truth_flag < 0.5) ++ev.false_immobilized_samples;
  }
  ev.velocity_rmse = ev.samples > 0 ? std::sqrt(ev.velocity_sq_sum / ev.samples) : std::nan("");
  if (ev.nees_samples > 0) ev.velocity_mean_nees = ev.nees_sum / ev.nees_samples;
  ev.disturbance_rmse = ev.disturbance_samples > 0
                            ? std::sqrt(ev.disturbance_sq_sum / ev.disturbance_samples)
                            : std::nan("");
  return ev;
}

Evaluation Combine(const std::vector<Evaluation>& runs, const std::string& name) {
  Evaluation total;
  total.name = name;
  for (const Evaluation& run : runs) {
    total.samples += run.samples;
    total.velocity_sq_sum += run.velocity_sq_sum;
    total.disturbance_sq_sum += run.disturbance_sq_sum;
    total.disturbance_samples += run.disturbance_samples;
    total.false_immobilized_samples += run.false_immobilized_samples;
    total.nees_sum += run.nees_sum;
    total.nees_samples += run.nees_samples;
    total.nees_within_95 += run.nees_within_95;
    total.events.insert(total.events.end(), run.events.begin(), run.events.end());
  }
  total.velocity_rmse =
      total.samples > 0 ? std::sqrt(total.velocity_sq_sum / total.samples) : std::nan("");
  if (total.nees_samples > 0) total.velocity_mean_nees = total.nees_sum / total.nees_samples;
  total.disturbance_rmse = total.disturbance_samples > 0
                               ? std::sqrt(total.disturbance_sq_sum / total.disturbance_samples)
                               : std::nan("");
  return total;
}

void PrintEvaluation(const Evaluation& ev, std::ostream& out) {
  out << std::fixed << std::setprecision(4) << ev.name << ": " << ev.samples
      << " samples, velocity RMSE " << ev.velocity_rmse << " m/s, disturbance RMSE "
      << ev.disturbance_rmse << " m/s^2, immobilized " << ev.detected() << "/" << ev.events.size()
      << " detected, mean delay " << ev.mean_detection_delay_s() << " s, false immobilized "
      << ev.false_immobilized_samples << " samples (" << 100.0 * ev.false_immobilized_fraction()
      << " %), v_bx NEES mean " << ev.velocity_mean_nees << ", within its 95 % bound "
      << 100.0 * ev.nees_within_95_fraction() << " %\n";
}

nlohmann::json ToJson(const Evaluation& ev) {
  nlohmann::json events = nlohmann::json::array();
  for (const EventScore& e : ev.events) {
    events.push_back({{"t_start", e.t_start},
                      {"t_end", e.t_end},
                      {"detected", e.detected},
                      {"delay_s", e.detected ? JsonNumber(e.delay_s) : nlohmann::json(nullptr)}});
  }
  return {{"name", ev.name},
          {"samples", ev.samples},
          {"velocity_rmse", JsonNumber(ev.velocity_rmse)},
          {"disturbance_rmse", JsonNumber(ev.disturbance_rmse)},
          {"events", ev.events.size()},
          {"detected", ev.detected()},
          {"mean_detection_delay_s", JsonNumber(ev.mean_detection_delay_s())},
          {"false_immobilized_samples", ev.false_immobilized_samples},
          {"false_immobilized_fraction", ev.false_immobilized_fraction()},
          {"velocity_mean_nees", JsonNumber(ev.velocity_mean_nees)},
          {"velocity_nees_within_95", JsonNumber(ev.nees_within_95_fraction())},
          {"event_details", events}};
}

}  // namespace slipgraph
