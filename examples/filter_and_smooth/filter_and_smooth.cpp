// The library from another program: read a drive log, run the EKF front end and the batch
// smoother, and print each one's velocity error against the log's truth (when it has one) and
// how many samples each flags immobilized.
// Usage: filter_and_smooth LOG_DIRECTORY
#include <slipgraph/evaluation/evaluation.h>
#include <slipgraph/io/estimate_file.h>
#include <slipgraph/io/log_reader.h>
#include <slipgraph/solvers/batch_smoother.h>
#include <slipgraph/solvers/ekf_runner.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

void Report(const char* name, const slipgraph::DriveLog& log,
            const std::vector<slipgraph::WardEstimate>& estimates) {
  long flagged = 0;
  for (const slipgraph::WardEstimate& e : estimates) flagged += e.slip.immobilized;
  std::printf("%-8s %zu estimates, %ld flagged immobilized", name, estimates.size(), flagged);
  if (!log.truth.empty()) {
    const slipgraph::Evaluation ev = slipgraph::Evaluate(log, slipgraph::EstimateTable(estimates));
    std::printf(", velocity RMSE %.4f m/s", ev.velocity_rmse);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s LOG_DIRECTORY\n", argv[0]);
    return 2;
  }
  try {
    const slipgraph::DriveLog log = slipgraph::ReadDriveLog(argv[1]);
    const slipgraph::ModelConfig model = slipgraph::DefaultModelConfig(log.vehicle);
    const slipgraph::FilterResult ekf = slipgraph::RunEkf(log, model);
    Report("EKF", log, ekf.estimates);
    const slipgraph::SmootherResult smoothed =
        slipgraph::SmoothBatch(log, model, ekf, slipgraph::BatchSmootherOptions());
    Report("smoother", log, smoothed.estimates);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return 1;
  }
}
