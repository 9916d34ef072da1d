#include <cmath>
#include <utility>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "evaluation/progress.h"
#include "solvers/batch_smoother.h"
#include "solvers/wilcox_graph.h"
#include "solvers/wilcox_velocity.h"
#include "solvers/window_smoother.h"

namespace slipgraph {

void RegisterSmoothCommand(CLI::App* app, int* status) {
  struct Options {
    EstimatorRunOptions run;
    bool no_gps = false;
    int threads = 1;
    double chunk_min = 0.0;
    double overlap_s = 60.0;
    bool advance_velocity = false;
    double advance_sd_m = 0.003;
    double stiffness_sd = std::nan("");  // PostProcessingStiffnessPriorSd
    double function_tolerance = BatchSmootherOptions().function_tolerance;
    double gnss_fading_fixes = EkfOptions().gnss_fading_fixes;  // the front end's
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = AddEstimatorCommand(
      app, "smooth", "Post-process a whole log with the Ceres batch smoother (EKF-initialised)",
      &options->run, &options->no_gps);
  cmd->add_option("--threads", options->threads, "Solver threads")->check(CLI::PositiveNumber);
  cmd->add_option("--function-tolerance", options->function_tolerance,
                  "The solve ends when a step lowers the cost by less than this fraction of it "
                  "(or would move no estimate by 0.01 of its sd); 1e-12 solves on to the optimum "
                  "where robust losses make it creep (docs/smoother.md)")
      ->check(CLI::Range(1e-16, 1e-1))
      ->capture_default_str();
  cmd->add_option("--chunk", options->chunk_min,
                  "Chunked mode for long logs: solve this many minutes at a time, joined to the "
                  "next chunk by a marginal prior (memory bounded by one chunk)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--overlap", options->overlap_s,
                  "Chunked mode: seconds of look-ahead every estimate has before it is final")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--advance-velocity", options->advance_velocity,
                "Rocker-bogie logs with articulation and ranging: Wilcox's advance per cycle "
                "(the factor graph, sides sharing the advance) as a body-velocity measurement");
  cmd->add_option("--advance-sd", options->advance_sd_m,
                  "sd of one cycle's advance for --advance-velocity where the graph gives none, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  AddStiffnessOption(cmd, &options->stiffness_sd);
  AddNoGnssFadingFlag(cmd, &options->gnss_fading_fixes);
  cmd->callback([options, status]() {
    BatchSmootherOptions base_options;
    base_options.filter.use_gps = !options->no_gps;
    base_options.filter.ekf.gnss_fading_fixes = options->gnss_fading_fixes;
    base_options.threads = options->threads;
    base_options.function_tolerance = options->function_tolerance;
    *status = RunEstimatorOverLogs(options->run, [&](const DriveLog& log, const ModelConfig& model,
                                                     std::ostream& report) {
      BatchSmootherOptions smoother_options = base_options;
      smoother_options.problem.stiffness_prior_sd =
          PostProcessingStiffnessPriorSd(model, options->stiffness_sd);
      ProgressPrinter progress(ShowsProgress(options->run), std::cerr);
      smoother_options.progress = progress.callback();
      if (options->advance_velocity) {
        WilcoxGraphOptions graph;
        graph.shared_advance = true;
        const WilcoxResult wilcox = EstimateWilcoxGraph(log, {}, graph);
        smoother_options.problem.body_velocity = WilcoxBodyVelocity(wilcox, options->advance_sd_m);
        report << "advance velocity: " << smoother_options.problem.body_velocity.size()
               << " cycles of Wilcox's factor graph (shared advance), each with its marginal sd\n";
      }
      if (options->chunk_min > 0.0) {
        const double rate_hz =
            log.wheels.size() > 1
                ? (log.wheels.size() - 1) / (log.wheels.back().t - log.wheels.front().t)
                : 100.0;
        WindowSmootherResult result = SmoothWindowed(
            log, model,
            ChunkedOptions(options->chunk_min, options->overlap_s, rate_hz, smoother_options));
        if (smoother_options.problem.stiffness_prior_sd > 0.0 && !model.ListsSoils()) {
          report << "note: the chunks keep the law's slip stiffness where the model lists no "
                    "soils (--stiffness-sd is for the whole-log solve there)\n";
        }
        report << DescribeWindowRun(result);
        return EstimatorOutput{std::move(result.estimates), {}};
      }
      const SmootherResult result = SmoothBatch(log, model, smoother_options);
      report << DescribeSmootherRun(result);
      // a_dist: every external force, the model's effect terms included.
      return EstimatorOutput{DisturbanceWithEffects(result, log, model), {}};
    });
  });
}

}  // namespace slipgraph
