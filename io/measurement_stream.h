// The log's sensor streams merged into one time-ordered sequence, as a filter consumes them.
// Entries point into the DriveLog's vectors; ties in time keep a fixed stream order (IMU first,
// then wheels, ...), so the sequence is deterministic.
#pragma once

#include <algorithm>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

enum class Stream { kImu, kWheels, kAttitude, kGps, kPose, kArticulation, kRange, kCommands };
constexpr int kStreamCount = 8;
const char* StreamName(Stream stream);  // the file name without ".csv"

struct StreamEntry {
  double t;
  Stream stream;
  int index;  // into the DriveLog vector of that stream
};

// Which streams a consumer uses (e.g. --no-gps clears gps).
struct StreamSelection {
  bool use[kStreamCount] = {true, true, true, true, true, true, true, true};
  bool Uses(Stream s) const { return use[static_cast<int>(s)]; }
  void Set(Stream s, bool on) { use[static_cast<int>(s)] = on; }
};

std::vector<StreamEntry> MergeStreams(const DriveLog& log, const StreamSelection& selection = {});

// Angular speed of the driven left and right sides (rad/s): the two wheels of diff_drive_castor
// and skid_steer, the mean of a side's three wheels for rocker_bogie6 (see factors/ward_state.h).
struct SideSpeeds {
  double left_radps;
  double right_radps;
};
SideSpeeds DrivenSideSpeeds(const WheelSample& sample, VehicleType type);

// Index of the latest sample (sorted by t) stamped at or before t + tolerance_s, or -1.
template <typename Samples>
long LatestAtOrBefore(const Samples& samples, double t, double tolerance_s = 0.0) {
  const auto it = std::upper_bound(samples.begin(), samples.end(), t + tolerance_s,
                                   [](double value, const auto& s) { return value < s.t; });
  return static_cast<long>(it - samples.begin()) - 1;
}

}  // namespace slipgraph
