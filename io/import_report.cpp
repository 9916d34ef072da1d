#include "io/import_report.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace slipgraph {
namespace {

bool AllFinite(std::initializer_list<double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// Sorts `samples` by time and drops those `readable` refuses or whose stamp repeats; reports a
// loss under `stream`.
template <typename Sample, typename Readable>
void Keep(const char* stream, std::vector<Sample>* samples, Readable readable,
          ImportReport* report) {
  std::stable_sort(samples->begin(), samples->end(),
                   [](const Sample& a, const Sample& b) { return a.t < b.t; });
  const size_t before = samples->size();
  std::vector<Sample> kept;
  kept.reserve(before);
  for (const Sample& s : *samples) {
    if (!std::isfinite(s.t) || !readable(s)) continue;
    if (!kept.empty() && s.t == kept.back().t) continue;
    kept.push_back(s);
  }
  *samples = std::move(kept);
  if (samples->size() < before) {
    report->lines.push_back(std::string(stream) + ": " + std::to_string(before - samples->size()) +
                            " of " + std::to_string(before) +
                            " samples dropped (a value not finite, or a stamp repeated)");
  }
}

}  // namespace

void KeepReadableSamples(DriveLog* log, ImportReport* report) {
  const int wheels = log->wheel_count();
  Keep(
      "imu", &log->imu,
      [](const ImuSample& s) {
        return AllFinite({s.ax, s.ay, s.az, s.gx, s.gy, s.gz});
      },
      report);
  Keep(
      "attitude", &log->attitude,
      [](const AttitudeSample& s) {
        return AllFinite({s.roll, s.pitch, s.yaw});
      },
      report);
  Keep(
      "wheels", &log->wheels,
      [wheels](const WheelSample& s) {
        return std::all_of(s.omega_radps.begin(), s.omega_radps.begin() + wheels,
                           [](double w) { return std::isfinite(w); });
      },
      report);
  Keep(
      "gps", &log->gps,
      [](const GpsSample& s) {
        return AllFinite({s.x, s.y, s.z, s.vx, s.vy, s.vz});
      },
      report);
}

}  // namespace slipgraph
