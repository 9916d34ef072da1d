#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {

void RegisterFilterCommand(CLI::App* app, int* status) {
  struct Options {
    EstimatorRunOptions run;
    bool no_gps = false;
    FilterRunOptions filter;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = AddEstimatorCommand(
      app, "filter", "Run the streaming EKF (Ward & Iagnemma) and write its estimates",
      &options->run, &options->no_gps);
  AddFrontEndOptions(cmd, &options->filter);
  cmd->callback([options, status]() {
    FilterRunOptions run_options = options->filter;
    run_options.use_gps = !options->no_gps;
    *status = RunEstimatorOverLogs(
        options->run, [&](const DriveLog& log, const ModelConfig& model, std::ostream& report) {
          const FilterResult result = RunEkf(log, model, run_options);
          report << DescribeFilterRun(result);
          return EstimatorOutput{result.estimates, {}};
        });
  });
}

}  // namespace slipgraph
