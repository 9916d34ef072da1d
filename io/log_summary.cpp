#include "io/log_summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/plausibility.h"

namespace slipgraph {
namespace {

// Gaps are intervals longer than this many median intervals.
constexpr double kGapFactor = 5.0;

template <typename Sample>
void AddStream(const char* name, const std::vector<Sample>& samples, bool present,
               LogSummary* summary) {
  if (!present) return;
  StreamSummary s;
  s.name = name;
  s.samples = samples.size();
  if (!samples.empty()) {
    s.t_first_s = samples.front().t;
    s.t_last_s = samples.back().t;
    std::vector<double> dts;
    for (size_t i = 1; i < samples.size(); ++i) {
      const double dt = samples[i].t - samples[i - 1].t;
      if (dt > 0.0) dts.push_back(dt);  // range rows share stamps
    }
    if (!dts.empty()) {
      std::vector<double> sorted = dts;
      std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
      const double median_dt = sorted[sorted.size() / 2];
      s.rate_hz = 1.0 / median_dt;
      double previous = samples.front().t;
      for (size_t i = 1; i < samples.size(); ++i) {
        const double dt = samples[i].t - previous;
        if (dt > kGapFactor * median_dt) s.gaps.emplace_back(previous, samples[i].t);
        if (dt > 0.0) previous = samples[i].t;
      }
    }
  }
  summary->streams.push_back(s);
}

std::string Seconds(double t) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << t;
  return out.str();
}

}  // namespace

LogSummary SummarizeLog(const DriveLog& log) {
  LogSummary summary;
  AddStream("imu", log.imu, log.Has("imu.csv"), &summary);
  AddStream("wheels", log.wheels, log.Has("wheels.csv"), &summary);
  AddStream("attitude", log.attitude, log.Has("attitude.csv"), &summary);
  AddStream("gps", log.gps, log.Has("gps.csv"), &summary);
  AddStream("pose", log.pose, log.Has("pose.csv"), &summary);
  AddStream("articulation", log.articulation, log.Has("articulation.csv"), &summary);
  AddStream("range", log.range, log.Has("range.csv"), &summary);
  AddStream("commands", log.commands, log.Has("commands.csv"), &summary);
  AddStream("truth", log.truth, log.Has("truth.csv"), &summary);

  summary.problems = log.warnings;
  bool first = true;
  for (const StreamSummary& s : summary.streams) {
    if (s.samples == 0) {
      summary.problems.push_back(s.name + ".csv has a header but no rows");
      continue;
    }
    summary.t_start_s = first ? s.t_first_s : std::min(summary.t_start_s, s.t_first_s);
    summary.t_end_s = first ? s.t_last_s : std::max(summary.t_end_s, s.t_last_s);
    first = false;
    for (const auto& gap : s.gaps) {
      summary.problems.push_back(s.name + ": gap of " + Seconds(gap.second - gap.first) +
                                 " s from t=" + Seconds(gap.first));
    }
  }
  // IMU and wheels drive every estimator: say when they do not cover the same time.
  if (!log.imu.empty() && !log.wheels.empty()) {
    const double start_gap = std::abs(log.imu.front().t - log.wheels.front().t);
    const double end_gap = std::abs(log.imu.back().t - log.wheels.back().t);
    if (start_gap > 1.0 || end_gap > 1.0) {
      summary.problems.push_back("imu and wheels cover different times (start differs by " +
                                 Seconds(start_gap) + " s, end by " + Seconds(end_gap) + " s)");
    }
  }
  // Physical plausibility (gravity at rest, wheels against GNSS and gyro): io/plausibility.
  for (std::string& problem : CheckPlausibility(log).problems) {
    summary.problems.push_back(std::move(problem));
  }
  return summary;
}

void PrintLogSummary(const DriveLog& log, const LogSummary& summary, std::ostream& out) {
  const Vehicle& v = log.vehicle;
  out << "log:      " << log.directory << "\n";
  out << "vehicle:  " << v.name << " (" << VehicleTypeName(v.type) << "), mass " << v.mass_kg
      << " kg, wheel radius " << v.wheel_radius_m << " m, track " << v.track_width_m << " m\n";
  out << "tire:     C1 " << v.tire.C1 << ", At " << v.tire.At << ", C2 " << v.tire.C2
      << "; rolling R1 " << v.rolling.R1 << ", A_roll " << v.rolling.A_roll << ", R2 "
      << v.rolling.R2 << "\n";
  out << "duration: " << Seconds(summary.t_end_s - summary.t_start_s) << " s (t "
      << Seconds(summary.t_start_s) << " to " << Seconds(summary.t_end_s) << ")\n";
  out << "streams:\n";
  for (const StreamSummary& s : summary.streams) {
    out << "  " << std::left << std::setw(13) << s.name << std::right << std::setw(9) << s.samples
        << " samples  " << std::setw(8) << std::fixed << std::setprecision(1) << s.rate_hz
        << " Hz  t " << Seconds(s.t_first_s) << " to " << Seconds(s.t_last_s) << "  gaps "
        << s.gaps.size() << "\n";
    out.unsetf(std::ios::fixed);
    out << std::setprecision(6);
  }
  for (const char* optional : {"attitude.csv", "gps.csv", "pose.csv", "articulation.csv",
                               "range.csv", "commands.csv", "truth.csv", "events.csv"}) {
    if (!log.Has(optional)) out << "  (no " << optional << ")\n";
  }
  if (!log.events.empty()) out << "events:   " << log.events.size() << " labelled intervals\n";
  if (summary.problems.empty()) {
    out << "problems: none found\n";
  } else {
    out << "problems: " << summary.problems.size() << "\n";
    for (const std::string& problem : summary.problems) out << "  - " << problem << "\n";
  }
}

}  // namespace slipgraph
