// A drive log's CSV files as columns, named and ordered as shared/log-format.md names them: what
// WriteDriveLog writes, and what a program that wants a stream as arrays (the Python module)
// reads, from one list of each file's columns.
#pragma once

#include <string>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

struct LogColumn {
  std::string name;
  bool is_text = false;            // the side of articulation.csv and range.csv, events' label
  std::vector<double> numbers;     // a numeric column's values (missing: NaN)
  std::vector<std::string> texts;  // a text column's values
  size_t size() const { return is_text ? texts.size() : numbers.size(); }
};

struct LogTable {
  std::string file;  // "imu.csv"
  std::vector<LogColumn> columns;
  size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
};

// The CSV files the log has: imu.csv and wheels.csv always, every other stream when it has
// samples or was read (DriveLog::present_files), in log-format.md's order.
std::vector<std::string> LogTableFiles(const DriveLog& log);

// The file `file` ("gps.csv") of the log as columns (the wheels' columns named by
// WheelNames(vehicle.type)). Throws std::invalid_argument for a name that is not a stream file of
// the format.
LogTable StreamTable(const DriveLog& log, const std::string& file);

}  // namespace slipgraph
