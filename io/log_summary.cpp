#include "io/log_summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/input_error.h"
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

// A sensor that repeats one value this long (and this many samples) reads as frozen or stuck.
constexpr double kFrozenMinS = 1.0;
constexpr size_t kFrozenMinSamples = 10;
// GNSS speed above which a wheel that does not change reads as stuck, m/s.
constexpr double kMovingMps = 0.3;

// Runs [first, last] of samples whose `same(previous, current)` holds throughout, lasting at
// least kFrozenMinS and kFrozenMinSamples.
template <typename Sample, typename Same>
std::vector<std::pair<size_t, size_t>> RepeatedRuns(const std::vector<Sample>& samples,
                                                    const Same& same) {
  std::vector<std::pair<size_t, size_t>> runs;
  size_t first = 0;
  for (size_t i = 1; i <= samples.size(); ++i) {
    if (i < samples.size() && same(samples[i - 1], samples[i])) continue;
    const size_t last = i - 1;
    if (last + 1 - first >= kFrozenMinSamples &&
        samples[last].t - samples[first].t >= kFrozenMinS) {
      runs.emplace_back(first, last);
    }
    first = i;
  }
  return runs;
}

// GNSS horizontal speed over [t0, t1] from the displacement between the first and last fix in
// it; NaN without two fixes half the span apart, or when the displacement is within 3 sd of the
// fixes' position noise (noisy fixes alone do not say the robot moved).
double GnssSpeedOver(const DriveLog& log, double t0, double t1) {
  const GpsSample* first = nullptr;
  const GpsSample* last = nullptr;
  for (const GpsSample& g : log.gps) {
    if (g.t < t0 || g.t > t1 || !std::isfinite(g.x) || !std::isfinite(g.y)) continue;
    if (first == nullptr) first = &g;
    last = &g;
  }
  if (first == nullptr || last->t - first->t < 0.5 * (t1 - t0)) return std::nan("");
  const double distance = std::hypot(last->x - first->x, last->y - first->y);
  const auto sd_of = [&log](const GpsSample& g) {
    return g.sd_xy > 0.0 ? g.sd_xy : log.vehicle.sensors.gps_sd_xy_m;
  };
  const double sd = std::hypot(sd_of(*first), sd_of(*last));
  if (!(distance > 3.0 * sd)) return std::nan("");
  return distance / (last->t - first->t);
}

// An IMU whose six channels all repeat (a stalled driver), and a wheel that repeats one reading
// while GNSS says the robot moves (a stuck or disconnected encoder).
void AddFrozenSensors(const DriveLog& log, std::vector<std::string>* problems) {
  const auto imu_same = [](const ImuSample& a, const ImuSample& b) {
    return a.ax == b.ax && a.ay == b.ay && a.az == b.az && a.gx == b.gx && a.gy == b.gy &&
           a.gz == b.gz;
  };
  for (const auto& [first, last] : RepeatedRuns(log.imu, imu_same)) {
    problems->push_back("imu: every channel frozen at one value for " +
                        Seconds(log.imu[last].t - log.imu[first].t) +
                        " s from t=" + Seconds(log.imu[first].t) + " (a stalled driver?)");
  }
  const std::vector<std::string>& names = WheelNames(log.vehicle.type);
  for (size_t w = 0; w < names.size(); ++w) {
    const auto wheel_same = [w](const WheelSample& a, const WheelSample& b) {
      return a.omega_radps[w] == b.omega_radps[w];
    };
    for (const auto& [first, last] : RepeatedRuns(log.wheels, wheel_same)) {
      const double t0 = log.wheels[first].t, t1 = log.wheels[last].t;
      const double speed = GnssSpeedOver(log, t0, t1);
      if (!(speed > kMovingMps)) continue;
      std::ostringstream value, moving;
      value << log.wheels[first].omega_radps[w];
      moving << std::fixed << std::setprecision(2) << speed;
      problems->push_back("wheels: " + names[w] + " unchanged at " + value.str() + " rad/s for " +
                          Seconds(t1 - t0) + " s from t=" + Seconds(t0) + " while GNSS moves at " +
                          moving.str() + " m/s (a stuck encoder?)");
    }
  }
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

  summary.reader_warnings = log.warnings;
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
  AddFrozenSensors(log, &summary.problems);
  // Physical plausibility (gravity at rest, wheels against GNSS and gyro): io/plausibility.
  Plausibility plausibility = CheckPlausibility(log);
  for (std::string& problem : plausibility.problems) {
    summary.problems.push_back(std::move(problem));
  }
  summary.plausibility = plausibility.figures;
  return summary;
}

std::vector<std::string> CheckLogForEstimation(const DriveLog& log) {
  for (const auto& [name, empty] : {std::pair<const char*, bool>{"imu.csv", log.imu.empty()},
                                    {"wheels.csv", log.wheels.empty()}}) {
    if (empty) {
      throw InputError(log.directory + "/" + name, 0, "", "",
                       "no rows: an estimator needs IMU and wheel data");
    }
  }
  const double imu_first = log.imu.front().t, imu_last = log.imu.back().t;
  const double wheels_first = log.wheels.front().t, wheels_last = log.wheels.back().t;
  if (imu_last < wheels_first || wheels_last < imu_first) {
    throw InputError(log.directory, 0, "", "",
                     "imu (t " + Seconds(imu_first) + " to " + Seconds(imu_last) +
                         ") and wheels (t " + Seconds(wheels_first) + " to " +
                         Seconds(wheels_last) +
                         ") share no time: are they stamped on different clocks?");
  }
  return SummarizeLog(log).problems;
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
  const std::string checks = DescribePlausibility(summary.plausibility);
  if (!checks.empty()) out << "checks:   " << checks << "\n";
  const size_t count = summary.reader_warnings.size() + summary.problems.size();
  if (count == 0) {
    out << "problems: none found\n";
  } else {
    out << "problems: " << count << "\n";
    for (const auto* list : {&summary.reader_warnings, &summary.problems}) {
      for (const std::string& problem : *list) out << "  - " << problem << "\n";
    }
  }
}

}  // namespace slipgraph
