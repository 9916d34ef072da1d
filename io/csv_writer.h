// Writes CSV in the drive-log dialect: a header line, one row per sample, numbers in the shortest
// form that reads back to the same double (std::to_chars), missing values as "nan".
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace slipgraph {

class CsvWriter {
 public:
  // Opens `path` for writing and writes the header. Throws InputError when it cannot be opened.
  CsvWriter(const std::string& path, const std::vector<std::string>& header);

  CsvWriter& operator<<(double value);
  CsvWriter& operator<<(const std::string& text);
  // Ends the row. Throws InputError naming the file when the write fails (a full disk).
  void EndRow();
  // Flushes and closes the file; throws InputError naming it when that fails. A writer that is
  // not closed is closed by its destructor, unchecked.
  void Close();

 private:
  void Separator();

  std::string path_;
  std::ofstream out_;
  std::string row_;
  bool row_started_ = false;
};

// Shortest round-trip text of a double ("nan" for NaN).
std::string FormatNumber(double value);

}  // namespace slipgraph
