#include "io/estimate_file.h"

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
  table.names = names;
  for (const std::string& name : names) table.columns[name];
  while (reader.Next()) {
    for (size_t c = 0; c < names.size(); ++c) {
      table.columns[names[c]].push_back(reader.Number(static_cast<int>(c)));
    }
  }
  return table;
}

}  // namespace slipgraph
