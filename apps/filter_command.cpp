#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {

void RegisterFilterCommand(CLI::App* app, int* status) {
  struct Options {
    EstimatorRunOptions run;
    bool no_gps = false;
  };
  auto options = std::make_shared<Options>();
  options->run.name = "filter";
  CLI::App* cmd = app->add_subcommand(
      "filter", "Run the streaming EKF (Ward & Iagnemma) and write its estimates");
  cmd->add_option("LOG", options->run.log, "Log or suite directory (default: the bundled sample)");
  cmd->add_option("--model", options->run.model,
                  "Model YAML overriding the vehicle's nominal values");
  cmd->add_flag("--no-gps", options->no_gps, "Leave GNSS out");
  cmd->add_flag("--skip-bad", options->run.skip_bad, "Drop bad input rows, with a warning each");
  cmd->add_option("--out", options->run.out,
                  "Estimate CSV (a suite: a directory, one CSV per log); default "
                  "./<log>_filter.csv or ./<suite>_filter/");
  cmd->callback([options, status]() {
    FilterRunOptions run_options;
    run_options.use_gps = !options->no_gps;
    RunEstimatorOverLogs(options->run,
                         [&](const DriveLog& log, const ModelConfig& model, std::ostream& report) {
                           const FilterResult result = RunEkf(log, model, run_options);
                           report << DescribeFilterRun(result);
                           return result.estimates;
                         });
    *status = 0;
  });
}

}  // namespace slipgraph
