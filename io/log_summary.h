// What `slipgraph info` reports about a log: vehicle, streams with rates, durations and gaps, and
// every problem found (reader warnings, defaulted keys, gaps, implausible values).
#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "io/drive_log.h"
#include "io/plausibility.h"

namespace slipgraph {

struct StreamSummary {
  std::string name;  // file name without ".csv"
  size_t samples = 0;
  double t_first_s = 0.0;
  double t_last_s = 0.0;
  double rate_hz = 0.0;  // from the median interval between distinct time stamps
  std::vector<std::pair<double, double>> gaps;  // [t_before, t_after] where dt > 5 x median
};

struct LogSummary {
  std::vector<StreamSummary> streams;  // present streams only
  double t_start_s = 0.0;
  double t_end_s = 0.0;
  std::vector<std::string> reader_warnings;  // the log reader's (DriveLog::warnings)
  std::vector<std::string> problems;         // found in the data: gaps, frozen sensors, ...
  PlausibilityFigures plausibility;          // what the physical checks measured
};

LogSummary SummarizeLog(const DriveLog& log);

// What every estimator checks before it runs. Throws InputError naming the log where estimates
// would mean nothing: no IMU or no wheel rows, or IMU and wheels that share no time (two time
// bases). Returns the problems SummarizeLog finds in the data (gaps, streams covering different
// times, frozen or stuck sensors, implausible values), one line each, for the caller to show as
// warnings beside the reader's own.
std::vector<std::string> CheckLogForEstimation(const DriveLog& log);
void PrintLogSummary(const DriveLog& log, const LogSummary& summary, std::ostream& out);

}  // namespace slipgraph
