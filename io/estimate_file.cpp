#include "io/estimate_file.h"

#include <stdexcept>
#include <string>

#include "io/csv_reader.h"

namespace slipgraph {
namespace {

std::vector<std::string> EstimateHeader(const std::vector<EstimateColumn>& columns) {
  std::vector<std::string> header = {"t"};
  for (const EstimateColumn& column : columns) {
    header.push_back(column.name);
    if (column.with_sd) header.push_back("sd_" + column.name);
  }
  return header;
}

}  // namespace

EstimateWriter::EstimateWriter(const std::string& path, std::vector<EstimateColumn> columns)
    : columns_(std::move(columns)), writer_(path, EstimateHeader(columns_)) {}

void EstimateWriter::Write(double t, const std::vector<double>& values,
                           const std::vector<double>& sds) {
  writer_ << t;
  for (size_t i = 0; i < columns_.size(); ++i) {
    writer_ << values[i];
    if (columns_[i].with_sd) writer_ << sds[i];
  }
  writer_.EndRow();
}

NumericTable ReadNumericTable(const std::string& path) {
  // First pass learns the header; the second reads every column as optional numbers.
  const std::vector<std::string> names = CsvReader(path, {}).header();
  std::vector<CsvColumn> columns;
  for (const std::string& name : names) columns.push_back({name, false});
  CsvReader reader(path, columns);
  NumericTable table;
  table.path = path;
  table.names = names;
  for (const std::string& name : names) table.columns[name];
  while (reader.Next()) {
    for (size_t c = 0; c < names.size(); ++c) {
      table.columns[names[c]].push_back(reader.Number(static_cast<int>(c)));
    }
  }
  return table;
}

void WriteEstimates(const std::vector<WardEstimate>& estimates, const std::string& path,
                    const std::vector<ExtraColumn>& extra) {
  std::vector<EstimateColumn> columns = {
      {"v_bx", true},        {"b_ax", true},      {"a_dist", true},       {"omega_left", true},
      {"omega_right", true}, {"yaw_rate", true},  {"b_gz", true},         {"slip_left", false},
      {"slip_right", false}, {"slip_ema", false}, {"immobilized", false}, {"accel_offset", false},
      {"gyro_offset", false}};
  const size_t standard = columns.size();
  for (const ExtraColumn& column : extra) {
    if (column.values.size() != estimates.size()) {
      throw std::logic_error("extra column '" + column.name + "' has " +
                             std::to_string(column.values.size()) + " values for " +
                             std::to_string(estimates.size()) + " estimates");
    }
    columns.push_back({column.name, false});
  }
  EstimateWriter writer(path, columns);
  std::vector<double> values(columns.size()), sds(columns.size(), 0.0);
  for (size_t row = 0; row < estimates.size(); ++row) {
    const WardEstimate& e = estimates[row];
    for (int i = 0; i < ward::kStateSize; ++i) values[i] = e.x[i], sds[i] = e.sd[i];
    values[7] = e.slip.slip_left;
    values[8] = e.slip.slip_right;
    values[9] = e.slip.slip_ema;
    values[10] = e.slip.immobilized ? 1.0 : 0.0;
    values[11] = e.accel_offset_mps2;
    values[12] = e.gyro_offset_radps;
    for (size_t j = 0; j < extra.size(); ++j) values[standard + j] = extra[j].values[row];
    writer.Write(e.t, values, sds);
  }
  writer.Close();
}

NumericTable EstimateTable(const std::vector<WardEstimate>& estimates) {
  NumericTable table;
  table.names = {"t", "v_bx", "sd_v_bx", "a_dist", "immobilized"};
  for (const WardEstimate& e : estimates) {
    table.columns["t"].push_back(e.t);
    table.columns["v_bx"].push_back(e.x[ward::kVbx]);
    table.columns["sd_v_bx"].push_back(e.sd[ward::kVbx]);
    table.columns["a_dist"].push_back(e.x[ward::kAdist]);
    table.columns["immobilized"].push_back(e.slip.immobilized ? 1.0 : 0.0);
  }
  return table;
}

}  // namespace slipgraph
