// Reads a drive log directory (shared/log-format.md) into a DriveLog.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/drive_log.h"

namespace slipgraph {

struct ReadOptions {
  // false: the first bad row or bad optional file is an InputError naming file, line, column and
  // value. true: bad rows are dropped and an optional file whose header is unusable is left out;
  // each is reported in DriveLog::warnings. Required files must exist and have their header.
  bool skip_bad = false;
  // With skip_bad: more bad rows in a file than this share of its rows (and more than 10) is an
  // InputError quoting the first: the file is not what the format says, and dropping the rest
  // (every row after a forward time typo, say) would lose what was good.
  double max_bad_fraction = 0.01;
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};

// Where a log's files come from: a directory, or texts held in memory (a test, a fuzzer, a
// program that made the log and has not written it).
struct LogFiles {
  std::string directory;  // the log's path, or what stands for it in errors
  // The text of the log's file `name` ("imu.csv"), nullopt when the log has no such file;
  // throws InputError naming the file when it exists but cannot be read.
  std::function<std::optional<std::string>(const std::string& name)> read;
};
// The files of the log directory `directory` (not read until asked for).
LogFiles LogFilesIn(const std::string& directory);
// Files held in memory, by name; `directory` stands for the log's path in errors.
LogFiles LogFilesInMemory(std::string directory, std::map<std::string, std::string> files);

// Throws InputError for a missing required file (vehicle.yaml, imu.csv, wheels.csv), a bad
// vehicle.yaml, and, unless skip_bad, any bad row: a missing required column, a non-numeric or
// non-finite cell, a missing value in a required column, a repeated or decreasing time stamp.
DriveLog ReadDriveLog(const std::string& directory, const ReadOptions& options = {});
// The same from files given by `files` (the directory check aside).
DriveLog ReadDriveLog(const LogFiles& files, const ReadOptions& options = {});

// True when `directory` holds a log (has vehicle.yaml); a suite is a directory of such.
bool IsLogDirectory(const std::string& directory);

// The logs at `path`: itself when it is a log, else its sub-directories that are logs, sorted.
// Throws InputError when there are none.
std::vector<std::string> ListLogs(const std::string& path);

}  // namespace slipgraph
