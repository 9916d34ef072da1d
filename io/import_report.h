// What the importers (matlab_import, rosbag_import) share: the report of how a recording was
// mapped, and the last step before they return a log, which must read back as the drive-log
// format requires (shared/log-format.md): each stream in time order with strictly increasing
// stamps and a finite number in every required column. A recording need not be so: a corrupted
// float, a message without a fix turned into NaN, two messages with one stamp.
#pragma once

#include <string>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

struct ImportReport {
  std::vector<std::string> lines;  // what was mapped how, one line each
};

// Sorts the IMU, attitude, wheel and GNSS streams by time (stably), then drops each sample with
// a non-finite value in a column the format requires or a stamp equal to the one before, and
// reports in `report` how many each stream lost.
void KeepReadableSamples(DriveLog* log, ImportReport* report);

}  // namespace slipgraph
