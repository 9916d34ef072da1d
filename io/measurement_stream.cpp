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
  Append(log.imu, Stream::kImu, selection, &entries);
  Append(log.wheels, Stream::kWheels, selection, &entries);
  Append(log.attitude, Stream::kAttitude, selection, &entries);
  Append(log.gps, Stream::kGps, selection, &entries);
  Append(log.pose, Stream::kPose, selection, &entries);
  Append(log.articulation, Stream::kArticulation, selection, &entries);
  Append(log.range, Stream::kRange, selection, &entries);
  Append(log.commands, Stream::kCommands, selection, &entries);
  // Each stream is already time-ordered, so a stable sort on t alone keeps the stream order on
  // ties and each stream's own order.
  std::stable_sort(entries.begin(), entries.end(),
                   [](const StreamEntry& a, const StreamEntry& b) { return a.t < b.t; });
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
