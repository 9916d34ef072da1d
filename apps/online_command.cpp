#include <iostream>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "evaluation/evaluation.h"
#include "evaluation/progress.h"
#include "solvers/wilcox_baseline.h"
#include "solvers/wilcox_velocity.h"
#include "solvers/window_smoother.h"

namespace slipgraph {

void RegisterOnlineCommand(CLI::App* app, int* status) {
  struct Options {
    EstimatorRunOptions run;
    bool no_gps = false;
    WindowSmootherOptions window;
    bool advance_velocity = false;
    double advance_sd_m = 0.003;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = AddEstimatorCommand(
      app, "online",
      "Online estimation: the EKF at every sample and a sliding-window smoother behind it "
      "(refined estimates with their lag)",
      &options->run, &options->no_gps);
  cmd->add_option("--window", options->window.window_s, "Window length, s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--update-every", options->window.update_every,
                  "Wheel samples between window solves")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--iterations", options->window.max_iterations,
                  "Gauss-Newton iterations per window solve")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  AddWindowSolverOption(cmd, &options->window.solver);
  AddFrontEndOptions(cmd, &options->window.filter);
  cmd->add_option("--stiffness-sd", options->window.stiffness_prior_sd,
                  "Estimate the tire law's slip stiffness in the window, with a prior of this "
                  "relative sd around the front end's law, when vehicle.yaml lists its soils "
                  "(law_samples); 0: the law as given")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--reject-distance", options->window.reject_distance_sd,
                  "Reject a window solve whose velocity leaves the front end's by more than this "
                  "many of its sd (RMS over the window) unless the window's GNSS (or another "
                  "estimator's velocity) fits it better: "
                  "the front end's estimate stands there (from_filter 1); 0: never")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag_callback(
      "--no-covariance", [options] { options->window.covariance = false; },
      "Skip the window's marginal covariance (report the EKF's sd)");
  cmd->add_flag("--advance-velocity", options->advance_velocity,
                "Rocker-bogie logs with articulation and ranging: Wilcox's advance per cycle (the "
                "baseline, causal, learning its prior's slip) as a body-velocity measurement, "
                "taken by the window when the cycle's scan arrives");
  cmd->add_option("--advance-sd", options->advance_sd_m,
                  "sd of one cycle's advance for --advance-velocity, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->footer(
      "The estimate file's standard columns are the window's refined estimates; ekf_* columns "
      "hold the front end's estimate at the same sample, lag_s when the refined one became "
      "final, from_filter 1 where a failed or rejected window left the EKF's estimate.");
  cmd->callback([options, status]() {
    options->window.filter.use_gps = !options->no_gps;
    *status = RunEstimatorOverLogs(
        options->run, [&](const DriveLog& log, const ModelConfig& model, std::ostream& report) {
          WindowSmootherOptions window = options->window;
          ProgressPrinter progress(ShowsProgress(options->run), std::cerr);
          window.progress = progress.callback();
          if (options->advance_velocity) {
            WilcoxOptions wilcox;
            wilcox.learn_slip = true;
            window.problem.body_velocity =
                WilcoxBodyVelocity(EstimateWilcoxBaseline(log, wilcox), options->advance_sd_m);
            window.problem.body_velocity_when_available = true;
            report << "advance velocity: " << window.problem.body_velocity.size()
                   << " cycles of Wilcox's baseline (learned slip), each taken at its scan\n";
          }
          const WindowSmootherResult result = SmoothWindowed(log, model, window);
          report << DescribeWindowRun(result);
          if (!log.truth.empty()) {
            Evaluation ekf = Evaluate(log, EstimateTable(result.ekf.estimates));
            ekf.name = "EKF front end of " + log.directory + " against truth";
            PrintEvaluation(ekf, report);
          }
          return EstimatorOutput{result.estimates, OnlineColumns(result)};
        });
  });
}

}  // namespace slipgraph
