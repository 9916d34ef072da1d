#include "workbench/diagnosis_series.h"

#include <filesystem>

namespace slipgraph {

std::vector<NamedTable> DiagnosisSeries(const Diagnosis& diagnosis) {
  std::vector<NamedTable> series;
  for (const StreamResiduals& stream : diagnosis.residuals.streams) {
    NamedTable named{"residual_" + stream.name + ".csv", {}};
    named.table.names = {"t", "normalized", "sd"};
    named.table.columns = {{"t", stream.t}, {"normalized", stream.normalized}, {"sd", stream.sd}};
    series.push_back(std::move(named));
  }
  for (const auto& [name, innovations] : diagnosis.solution.ekf.stats.innovations) {
    NamedTable named{"innovation_" + name + ".csv", {}};
    named.table.names = {"t", "normalized"};
    named.table.columns = {{"t", innovations.t}, {"normalized", innovations.normalized}};
    series.push_back(std::move(named));
  }
  return series;
}

std::vector<std::string> WriteSeries(const std::vector<NamedTable>& series,
                                     const std::string& directory) {
  std::filesystem::create_directories(directory);
  std::vector<std::string> written;
  for (const NamedTable& named : series) {
    written.push_back((std::filesystem::path(directory) / named.file).string());
    WriteNumericTable(named.table, written.back());
  }
  return written;
}

}  // namespace slipgraph
