#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "solvers/batch_smoother.h"

namespace slipgraph {

void RegisterSmoothCommand(CLI::App* app, int* status) {
  struct Options {
    EstimatorRunOptions run;
    bool no_gps = false;
    int threads = 1;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = AddEstimatorCommand(
      app, "smooth", "Post-process a whole log with the Ceres batch smoother (EKF-initialised)",
      &options->run, &options->no_gps);
  cmd->add_option("--threads", options->threads, "Solver threads")->check(CLI::PositiveNumber);
  cmd->callback([options, status]() {
    BatchSmootherOptions smoother_options;
    smoother_options.filter.use_gps = !options->no_gps;
    smoother_options.threads = options->threads;
    RunEstimatorOverLogs(options->run,
                         [&](const DriveLog& log, const ModelConfig& model, std::ostream& report) {
                           const SmootherResult result = SmoothBatch(log, model, smoother_options);
                           report << DescribeSmootherRun(result);
                           return EstimatorOutput{result.estimates, {}};
                         });
    *status = 0;
  });
}

}  // namespace slipgraph
