#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {

void RegisterFilterCommand(CLI::App* app, int* status) {
  struct Options {
    EstimatorRunOptions run;
    bool no_gps = false;
    bool single_law = false;
    bool gnss_fading = false;
    bool disturbance_modes = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = AddEstimatorCommand(
      app, "filter", "Run the streaming EKF (Ward & Iagnemma) and write its estimates",
      &options->run, &options->no_gps);
  cmd->add_flag("--single-law", options->single_law,
                "One filter on the user's tire law (the paper's), also when vehicle.yaml lists the "
                "soils it was fitted over (law_samples: by default a bank of filters, one per law, "
                "weighed by their GNSS likelihood)");
  cmd->add_flag("--gnss-fading", options->gnss_fading,
                "Fading memory on GNSS: widen the filter's covariance when its GNSS innovations "
                "keep one sign, so that GNSS pulls a drifting velocity back (EkfOptions::"
                "gnss_fading_*; docs/mismatch.md)");
  cmd->add_flag("--disturbance-modes", options->disturbance_modes,
                "The single filter as three disturbance modes (none, changing, held) mixed as an "
                "interacting multiple model: fewer false alarms where the model's tire law or "
                "attitude is off, some slow hold-backs missed (solvers/disturbance_imm.h; "
                "docs/mismatch.md)");
  cmd->callback([options, status]() {
    FilterRunOptions run_options;
    if (options->gnss_fading) run_options.ekf.gnss_fading_fixes = kGnssFadingFixes;
    run_options.use_gps = !options->no_gps;
    run_options.multiple_model = !options->single_law;
    run_options.disturbance_modes = options->disturbance_modes;
    *status = RunEstimatorOverLogs(
        options->run, [&](const DriveLog& log, const ModelConfig& model, std::ostream& report) {
          const FilterResult result = RunEkf(log, model, run_options);
          report << DescribeFilterRun(result);
          return EstimatorOutput{result.estimates, {}};
        });
  });
}

}  // namespace slipgraph
