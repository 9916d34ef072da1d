// Estimate files: CSV with a header, SI units, one row per estimate time, each value's standard
// deviation beside it as sd_<name>. Written by every solver, read by `evaluate`.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "io/csv_writer.h"
#include "io/state_estimate.h"

namespace slipgraph {

struct EstimateColumn {
  std::string name;     // e.g. "v_bx"; SI units implied by the name's documentation
  bool with_sd = true;  // writes sd_<name> right after it
};

class EstimateWriter {
 public:
  EstimateWriter(const std::string& path, std::vector<EstimateColumn> columns);
  // values and sds are indexed like the columns; sds of columns without sd are ignored.
  void Write(double t, const std::vector<double>& values, const std::vector<double>& sds);
  // Flushes and closes the file (CsvWriter::Close: throws when the write failed).
  void Close() { writer_.Close(); }

 private:
  std::vector<EstimateColumn> columns_;
  CsvWriter writer_;
};

// Every column of a numeric CSV by name ("t" included). Throws InputError naming file, line,
// column and value on a bad cell (missing values are NaN).
struct NumericTable {
  std::string path;  // the file it was read from (empty: built in memory)
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> columns;
  size_t rows() const { return columns.empty() ? 0 : columns.begin()->second.size(); }
};
NumericTable ReadNumericTable(const std::string& path);

// A column an estimator adds after the standard ones (one value per estimate).
struct ExtraColumn {
  std::string name;
  std::vector<double> values;
};

// Estimate file: t, v_bx, b_ax, a_dist, omega_left, omega_right, yaw_rate, b_gz (each with
// sd_), slip_left, slip_right, slip_ema, immobilized, accel_offset, gyro_offset, then `extra`.
void WriteEstimates(const std::vector<WardEstimate>& estimates, const std::string& path,
                    const std::vector<ExtraColumn>& extra = {});
// The estimates as the table `evaluate` reads (t, v_bx, sd_v_bx, a_dist, immobilized), without
// a file.
NumericTable EstimateTable(const std::vector<WardEstimate>& estimates);

}  // namespace slipgraph
