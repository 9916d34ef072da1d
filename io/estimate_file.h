// Estimate files: CSV with a header, SI units, one row per estimate time, each value's standard
// deviation beside it as sd_<name>. Written by every solver, read by `evaluate`.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "io/state_estimate.h"

namespace slipgraph {

// Every column of a numeric CSV by name ("t" included). Throws InputError naming file, line,
// column and value on a bad cell (missing values are NaN).
struct NumericTable {
  std::string path;  // the file it was read from (empty: built in memory)
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> columns;
  size_t rows() const { return columns.empty() ? 0 : columns.begin()->second.size(); }
};
NumericTable ReadNumericTable(const std::string& path);
// Writes the table's columns in `names` order with a header (CsvWriter's numbers). Throws
// InputError when the file cannot be written, std::logic_error when a column is short.
void WriteNumericTable(const NumericTable& table, const std::string& path);

// A column an estimator adds after the standard ones (one value per estimate).
struct ExtraColumn {
  std::string name;
  std::vector<double> values;
};

// The estimate file's column of each state component, in the state's order (ward::kVbx ...).
inline constexpr const char* kStateColumns[ward::kStateSize] = {
    "v_bx", "b_ax", "a_dist", "omega_left", "omega_right", "yaw_rate", "b_gz"};

// Every column of the estimate file (docs/estimate-file.md): t, v_bx, b_ax, a_dist, omega_left,
// omega_right, yaw_rate, b_gz (each followed by its sd_), slip_left, slip_right, slip_ema,
// immobilized, accel_offset, gyro_offset, then `extra`. Throws std::logic_error when an extra
// column's length is not the estimates'.
NumericTable EstimateColumns(const std::vector<WardEstimate>& estimates,
                             const std::vector<ExtraColumn>& extra = {});
// EstimateColumns written as a CSV file.
void WriteEstimates(const std::vector<WardEstimate>& estimates, const std::string& path,
                    const std::vector<ExtraColumn>& extra = {});
// The estimates as the table `evaluate` reads (t, v_bx, sd_v_bx, a_dist, immobilized), without
// a file.
NumericTable EstimateTable(const std::vector<WardEstimate>& estimates);

}  // namespace slipgraph
