#include "io/estimate_file.h"

#include <stdexcept>
#include <string>

#include "io/csv_reader.h"
#include "io/csv_writer.h"

namespace slipgraph {
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

void WriteNumericTable(const NumericTable& table, const std::string& path) {
  std::vector<const std::vector<double>*> columns;
  for (const std::string& name : table.names) {
    columns.push_back(&table.columns.at(name));
    if (columns.back()->size() != columns.front()->size()) {
      throw std::logic_error("column '" + name + "' of the table for " + path + " has " +
                             std::to_string(columns.back()->size()) + " values, not " +
                             std::to_string(columns.front()->size()));
    }
  }
  CsvWriter writer(path, table.names);
  for (size_t row = 0; row < table.rows(); ++row) {
    for (const std::vector<double>* column : columns) writer << (*column)[row];
    writer.EndRow();
  }
  writer.Close();
}

NumericTable EstimateColumns(const std::vector<WardEstimate>& estimates,
                             const std::vector<ExtraColumn>& extra) {
  NumericTable table;
  const auto add = [&](const std::string& name) -> std::vector<double>& {
    table.names.push_back(name);
    std::vector<double>& column = table.columns[name];
    column.reserve(estimates.size());
    return column;
  };
  std::vector<double>& t = add("t");
  for (const WardEstimate& e : estimates) t.push_back(e.t);
  for (int i = 0; i < ward::kStateSize; ++i) {
    std::vector<double>& value = add(kStateColumns[i]);
    for (const WardEstimate& e : estimates) value.push_back(e.x[i]);
    std::vector<double>& sd = add(std::string("sd_") + kStateColumns[i]);
    for (const WardEstimate& e : estimates) sd.push_back(e.sd[i]);
  }
  const auto add_each = [&](const std::string& name, auto value_of) {
    std::vector<double>& column = add(name);
    for (const WardEstimate& e : estimates) column.push_back(value_of(e));
  };
  add_each("slip_left", [](const WardEstimate& e) { return e.slip.slip_left; });
  add_each("slip_right", [](const WardEstimate& e) { return e.slip.slip_right; });
  add_each("slip_ema", [](const WardEstimate& e) { return e.slip.slip_ema; });
  add_each("immobilized", [](const WardEstimate& e) { return e.slip.immobilized ? 1.0 : 0.0; });
  add_each("accel_offset", [](const WardEstimate& e) { return e.accel_offset_mps2; });
  add_each("gyro_offset", [](const WardEstimate& e) { return e.gyro_offset_radps; });
  for (const ExtraColumn& column : extra) {
    if (column.values.size() != estimates.size()) {
      throw std::logic_error("extra column '" + column.name + "' has " +
                             std::to_string(column.values.size()) + " values for " +
                             std::to_string(estimates.size()) + " estimates");
    }
    add(column.name) = column.values;
  }
  return table;
}

void WriteEstimates(const std::vector<WardEstimate>& estimates, const std::string& path,
                    const std::vector<ExtraColumn>& extra) {
  WriteNumericTable(EstimateColumns(estimates, extra), path);
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
