// The series behind a diagnosis' statistics, as tables to plot elsewhere: per stream, the
// smoother's normalized residuals at its solution (residual_<stream>.csv: t, normalized, sd) and
// the front end's normalized innovations (innovation_<stream>.csv: t, normalized). A model that
// fits leaves both white with unit variance.
#pragma once

#include <string>
#include <vector>

#include "io/estimate_file.h"
#include "workbench/diagnosis.h"

namespace slipgraph {

struct NamedTable {
  std::string file;  // "residual_gnss.csv"
  NumericTable table;
};

std::vector<NamedTable> DiagnosisSeries(const Diagnosis& diagnosis);

// Writes each table as `directory`/file (creating the directory); returns the paths written.
std::vector<std::string> WriteSeries(const std::vector<NamedTable>& series,
                                     const std::string& directory);

}  // namespace slipgraph
