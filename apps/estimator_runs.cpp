#include "apps/estimator_runs.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "apps/commands.h"
#include "evaluation/evaluation.h"
#include "evaluation/progress.h"
#include "io/estimate_file.h"
#include "io/input_error.h"
#include "io/log_reader.h"
#include "io/log_summary.h"
#include "io/yaml_config.h"
#include "solvers/batch_smoother.h"
#include "solvers/ekf_runner.h"
#include "solvers/trust_check.h"

namespace slipgraph {

void AddReadOptions(CLI::App* cmd, ReadOptions* read) {
  cmd->add_flag("--skip-bad", read->skip_bad,
                "Drop bad input rows and unusable optional files, with a warning each");
  cmd->add_option("--max-bad", read->max_bad_fraction,
                  "With --skip-bad: the largest share of a file's rows that may be dropped (more, "
                  "and more than 10 rows, is an error quoting the first bad row)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
}

DriveLog ReadLogWithWarnings(const std::string& path, const ReadOptions& read,
                             std::ostream& warnings) {
  DriveLog log = ReadDriveLog(path, read);
  for (const std::string& warning : log.warnings) warnings << "warning: " << warning << "\n";
  for (const std::string& problem : CheckLogForEstimation(log)) {
    warnings << "warning: " << path << ": " << problem << "\n";
  }
  return log;
}

CLI::App* AddEstimatorCommand(CLI::App* app, const std::string& name,
                              const std::string& description, EstimatorRunOptions* run,
                              bool* no_gps) {
  run->name = name;
  CLI::App* cmd = app->add_subcommand(name, description);
  cmd->add_option("LOG", run->log, "Log or suite directory (default: the bundled sample)")
      ->check(NonEmptyPath());
  cmd->add_option("--model", run->model, "Model YAML overriding the vehicle's nominal values");
  cmd->add_flag("--no-gps", *no_gps, "Leave GNSS out");
  AddReadOptions(cmd, &run->read);
  cmd->add_flag("--strict", run->strict,
                "Exit with status 3 when the trust check fails on a log (estimates still "
                "written)");
  cmd->add_option("--out", run->out,
                  "Estimate CSV (a suite: a directory, one CSV per log); default ./<log>_" + name +
                      ".csv or ./<suite>_" + name + "/");
  run->json.Add(cmd);
  AddSuiteOptions(cmd, &run->suite);
  cmd->add_flag("--quiet", run->quiet,
                "No progress line on stderr (shown on a terminal for runs over 2 s, one log at a "
                "time)");
  return cmd;
}

bool ShowsProgress(const EstimatorRunOptions& run) {
  return !run.quiet && run.suite.jobs <= 1 && StderrIsTerminal();
}

int RunEstimatorOverLogs(const EstimatorRunOptions& options, const Estimator& estimate) {
  namespace fs = std::filesystem;
  const std::string path = options.log.empty() ? DefaultLogPath() : options.log;
  const std::vector<std::string> logs = ListLogs(path);
  const bool suite = !IsLogDirectory(path);
  const std::string name = fs::path(path).filename().string();
  std::string out = options.out;
  if (out.empty()) out = name + "_" + options.name + (suite ? "" : ".csv");
  // A log's estimate file: `out` itself, or one CSV per log in the suite's directory `out`.
  const auto output_of = [&](const std::string& log_dir) {
    return suite ? (fs::path(out) / (fs::path(log_dir).filename().string() + ".csv")).string()
                 : out;
  };
  // The output may not be one of the inputs: a log's own file would be overwritten.
  for (const std::string& log_dir : logs) {
    const std::string file = output_of(log_dir);
    if (!fs::exists(file)) continue;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(log_dir, error)) {
      if (fs::equivalent(entry.path(), file, error)) {
        throw InputError(
            file, 0, "", "",
            "the output is a file of the log " + log_dir + ": refusing to overwrite it");
      }
    }
  }
  if (suite) fs::create_directories(out);
  std::vector<nlohmann::json> records(logs.size());
  const std::vector<LogFailure> failures = RunOverLogs(
      logs, options.suite,
      [&](size_t i, std::ostream& out, std::ostream& err) {
        const std::string& log_dir = logs[i];
        DriveLog log = ReadLogWithWarnings(log_dir, options.read, err);
        const ModelConfig model = ModelForLog(&log, options.model);
        const std::string file = output_of(log_dir);
        err << options.name << ": " << log_dir << " -> " << file << "\n";
        std::ostringstream report;
        EstimatorOutput output = estimate(log, model, report);
        err << report.str();
        // Whether the estimates hold against the log's own wheels and GNSS
        // (solvers/trust_check.h).
        TrustOptions trust_options;
        trust_options.gnss_heading_from_course = model.gnss_heading_from_course;
        const TrustReport trust = CheckTrust(log, output.estimates, trust_options);
        err << DescribeTrust(trust)
            << (trust.trusted ? "" : "  the estimate file's column `suspect` marks the samples\n");
        output.extra.push_back({"suspect", trust.suspect});
        WriteEstimates(output.estimates, file, output.extra);
        nlohmann::json record = {{"log", log_dir},
                                 {"estimates", file},
                                 {"model", ModelRecord(options.model, model)},
                                 {"trusted", trust.trusted},
                                 {"trust_warnings", trust.warnings},
                                 {"report", report.str()},
                                 {"evaluation", nullptr}};
        if (!log.truth.empty()) {
          Evaluation ev = Evaluate(log, ReadNumericTable(file));
          ev.name = log_dir + " against truth";
          PrintEvaluation(ev, out);
          record["evaluation"] = ToJson(ev);
        }
        records[i] = record;
      },
      options.json.text(), std::cerr);
  int untrusted = 0;
  for (const nlohmann::json& record : records) {
    untrusted += record.contains("trusted") && !record["trusted"].get<bool>() ? 1 : 0;
  }
  for (const LogFailure& failure : failures) {
    records[failure.index] = {{"log", failure.log}, {"error", failure.error}};
  }
  if (options.json.enabled()) {
    options.json.Write({{"logs", records},
                        {"untrusted", untrusted},
                        {"failed", static_cast<int>(failures.size())}});
  }
  PrintFailures(options.name, failures, logs.size(), std::cerr);
  if (!failures.empty()) return kFailedLogsExit;
  if (options.strict && untrusted > 0) {
    std::cerr << options.name << ": --strict: " << untrusted << " of " << logs.size()
              << " log(s) not trusted\n";
    return kUntrustedExit;
  }
  return 0;
}

CLI::Validator NonEmptyPath() {
  return CLI::Validator(
      [](std::string& path) {
        return path.empty() ? std::string("an empty path (no argument takes the bundled sample)")
                            : std::string();
      },
      "PATH");
}

void AddWindowSolverOption(CLI::App* cmd, WindowSolver* solver) {
  cmd->add_option_function<std::string>(
         "--solver",
         [solver](const std::string& name) {
           *solver = name == "ceres" ? WindowSolver::kCeres : WindowSolver::kChainGaussNewton;
         },
         "Window solver: chain (Gauss-Newton on the window's chain structure, the low-latency "
         "one) or ceres (ceres::Solve, Levenberg-Marquardt)")
      ->check(CLI::IsMember({"chain", "ceres"}))
      ->default_str(*solver == WindowSolver::kCeres ? "ceres" : "chain");
}

void AddFrontEndOptions(CLI::App* cmd, FilterRunOptions* filter) {
  cmd->add_flag_callback(
      "--single-law", [filter] { filter->multiple_model = false; },
      "One filter on the user's tire law, also when vehicle.yaml lists the soils "
      "it was fitted over (law_samples: by default a bank of filters, one per law, weighed by "
      "their GNSS likelihood)");
  AddNoGnssFadingFlag(cmd, &filter->ekf.gnss_fading_fixes);
  cmd->add_flag_callback(
      "--disturbance-modes", [filter] { filter->disturbance_modes = true; },
      "The single filter as three disturbance modes (quiet, changing, held) mixed as an "
      "interacting multiple model: fewer false alarms where the model's tire law or attitude is "
      "off, some slow hold-backs missed (solvers/disturbance_imm.h; docs/mismatch.md). Where "
      "vehicle.yaml lists law_samples the bank runs instead: add --single-law");
}

void AddNoGnssFadingFlag(CLI::App* cmd, double* fading_fixes) {
  cmd->add_flag_callback(
      "--no-gnss-fading", [fading_fixes] { *fading_fixes = 0.0; },
      "No fading memory on GNSS in the single front end (with --single-law or without law "
      "samples). By default its covariance widens when its GNSS innovations "
      "keep one sign, so that GNSS pulls a drifting velocity back (EkfOptions::gnss_fading_*; "
      "docs/mismatch.md)");
}

void AddStiffnessOption(CLI::App* cmd, double* prior_sd) {
  char prior[16];
  std::snprintf(prior, sizeof(prior), "%g", kPostProcessingStiffnessPriorSd);
  cmd->add_option("--stiffness-sd", *prior_sd,
                  "Batch smoother: estimate the tire law's slip stiffness (the terrain is not the "
                  "law's), with a prior of this relative sd around the law's, kept only when "
                  "its velocities fit GNSS about as well as the law's as given (a second smooth; "
                  "docs/mismatch.md); 0: the law as given. Default: " +
                      std::string(prior) +
                      " where the model lists its soils (law_samples), else the law as given. "
                      "Not with model effects; in smooth's --chunk mode only where the model "
                      "lists its soils")
      ->check(CLI::NonNegativeNumber);
}

}  // namespace slipgraph
