#include "io/measurement_stream.h"

#include <algorithm>

namespace slipgraph {
namespace {

template <typename Sample>
void Append(const std::vector<Sample>& samples, Stream stream, const StreamSelection& selection,
            std::vector<StreamEntry>* entries) {
  if (!selection.Uses(stream)) return;
  for (size_t i = 0; i < samples.size(); ++i) {
    entries->push_back({samples[i].t, stream, static_cast<int>(i)});
  }
}

}  // namespace

const char* StreamName(Stream stream) {
  static const char* const kNames[kStreamCount] = {"imu",  "wheels",       "attitude", "gps",
                                                   "pose", "articulation", "range",    "commands"};
  return kNames[static_cast<int>(stream)];
}

std::vector<StreamEntry> MergeStreams(const DriveLog& log, const StreamSelection& selection) {
  std::vector<StreamEntry> entries;
  entries.reserve(log.imu.size() + log.wheels.size() + log.attitude.size() + log.gps.size() +
                  log.pose.size() + log.articulation.size() + log.range.size() +
                  log.commands.size());
  // Each stream's entries form one run; the runs are merged in stream order, so on equal times
  // the earlier stream comes first and each stream keeps its own order (a stable sort by t).
  std::vector<size_t> run_end;
  const auto append = [&](const auto& samples, Stream stream) {
    Append(samples, stream, selection, &entries);
    run_end.push_back(entries.size());
  };
  append(log.imu, Stream::kImu);
  append(log.wheels, Stream::kWheels);
  append(log.attitude, Stream::kAttitude);
  append(log.gps, Stream::kGps);
  append(log.pose, Stream::kPose);
  append(log.articulation, Stream::kArticulation);
  append(log.range, Stream::kRange);
  append(log.commands, Stream::kCommands);
  const auto by_time = [](const StreamEntry& a, const StreamEntry& b) { return a.t < b.t; };
  bool runs_sorted = true;
  size_t begin = 0;
  for (size_t end : run_end) {
    runs_sorted =
        runs_sorted && std::is_sorted(entries.begin() + begin, entries.begin() + end, by_time);
    begin = end;
  }
  if (runs_sorted) {  // the usual case: merge the sorted runs, O(n) per run
    for (size_t r = 1; r < run_end.size(); ++r) {
      std::inplace_merge(entries.begin(), entries.begin() + run_end[r - 1],
                         entries.begin() + run_end[r], by_time);
    }
  } else {
    std::stable_sort(entries.begin(), entries.end(), by_time);
  }
  return entries;
}

SideSpeeds DrivenSideSpeeds(const WheelSample& sample, VehicleType type) {
  const auto& w = sample.omega_radps;
  if (type == VehicleType::kRockerBogie6) {
    // Column order fl, ml, rl, fr, mr, rr (WheelNames).
    return {(w[0] + w[1] + w[2]) / 3.0, (w[3] + w[4] + w[5]) / 3.0};
  }
  return {w[0], w[1]};
}

}  // namespace slipgraph
