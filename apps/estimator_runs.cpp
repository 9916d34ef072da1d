#include "apps/estimator_runs.h"

#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "evaluation/evaluation.h"
#include "io/estimate_file.h"
#include "io/log_reader.h"
#include "io/yaml_config.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {

void RunEstimatorOverLogs(const EstimatorRunOptions& options, const Estimator& estimate) {
  namespace fs = std::filesystem;
  const std::string path = options.log.empty() ? DefaultLogPath() : options.log;
  const std::vector<std::string> logs = ListLogs(path);
  const bool suite = !IsLogDirectory(path);
  const std::string name = fs::path(path).filename().string();
  std::string out = options.out;
  if (out.empty()) out = name + "_" + options.name + (suite ? "" : ".csv");
  if (suite) fs::create_directories(out);
  ReadOptions read_options;
  read_options.skip_bad = options.skip_bad;
  for (const std::string& log_dir : logs) {
    const DriveLog log = ReadDriveLog(log_dir, read_options);
    for (const std::string& warning : log.warnings) std::cerr << "warning: " << warning << "\n";
    const ModelConfig model = options.model.empty() ? DefaultModelConfig(log.vehicle)
                                                    : ReadModelYaml(options.model, log.vehicle);
    const std::string file =
        suite ? (fs::path(out) / (fs::path(log_dir).filename().string() + ".csv")).string() : out;
    std::cerr << options.name << ": " << log_dir << " -> " << file << "\n";
    FilterResult rows;
    rows.estimates = estimate(log, model, std::cerr);
    WriteEkfEstimates(rows, file);
    if (!log.truth.empty()) {
      Evaluation ev = Evaluate(log, ReadNumericTable(file));
      ev.name = log_dir + " against truth";
      PrintEvaluation(ev, std::cout);
    }
  }
}

}  // namespace slipgraph
