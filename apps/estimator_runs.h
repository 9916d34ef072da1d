// The loop the estimator subcommands (filter, smooth) share: resolve the log or suite and the
// output path, read each log and its model, run the estimator, write its estimates, report, and,
// when the log has truth, print how the estimates compare with it (as `evaluate` would).
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "model/model_config.h"
#include "solvers/ward_ekf.h"

namespace slipgraph {

struct EstimatorRunOptions {
  std::string log;    // empty: the bundled sample
  std::string model;  // empty: the vehicle's nominal model
  std::string out;    // empty: ./<log>_<name>.csv, or ./<suite>_<name>/ for a suite
  bool skip_bad = false;
  std::string name;  // "filter", "smooth": the default output suffix and report prefix
};

// `estimate` runs one log and writes its own report lines to `report`.
using Estimator = std::function<std::vector<EkfEstimate>(
    const DriveLog& log, const ModelConfig& model, std::ostream& report)>;

void RunEstimatorOverLogs(const EstimatorRunOptions& options, const Estimator& estimate);

}  // namespace slipgraph
