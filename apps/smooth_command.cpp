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
  options->run.name = "smooth";
  CLI::App* cmd = app->add_subcommand(
      "smooth", "Post-process a whole log with the Ceres batch smoother (EKF-initialised)");
  cmd->add_option("LOG", options->run.log, "Log or suite directory (default: the bundled sample)");
  cmd->add_option("--model", options->run.model,
                  "Model YAML overriding the vehicle's nominal values");
  cmd->add_flag("--no-gps", options->no_gps, "Leave GNSS out");
  cmd->add_flag("--skip-bad", options->run.skip_bad, "Drop bad input rows, with a warning each");
  cmd->add_option("--threads", options->threads, "Solver threads")->check(CLI::PositiveNumber);
  cmd->add_option("--out", options->run.out,
                  "Estimate CSV (a suite: a directory, one CSV per log); default "
                  "./<log>_smooth.csv or ./<suite>_smooth/");
  cmd->callback([options, status]() {
    BatchSmootherOptions smoother_options;
    smoother_options.filter.use_gps = !options->no_gps;
    smoother_options.threads = options->threads;
    RunEstimatorOverLogs(options->run,
                         [&](const DriveLog& log, const ModelConfig& model, std::ostream& report) {
                           const SmootherResult result = SmoothBatch(log, model, smoother_options);
                           report << DescribeSmootherRun(result);
                           return result.estimates;
                         });
    *status = 0;
  });
}

}  // namespace slipgraph
