// What the subcommands share: reading a log with its warnings, its model, and the loop the
// estimator subcommands (filter, smooth, online) share: resolve the log or suite and the
// output path, read each log and its model, run the estimator, write its estimates, report, and,
// when the log has truth, print how the estimates compare with it (as `evaluate` would).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <ostream>
#include <string>
#include <vector>

#include "apps/json_output.h"
#include "apps/suite_runs.h"
#include "io/drive_log.h"
#include "io/log_reader.h"
#include "model/model_config.h"
#include "solvers/ekf_runner.h"
#include "solvers/window_smoother.h"

namespace slipgraph {

struct EstimatorRunOptions {
  std::string log;    // empty: the bundled sample
  std::string model;  // empty: the vehicle's nominal model
  std::string out;    // empty: ./<log>_<name>.csv, or ./<suite>_<name>/ for a suite
  ReadOptions read;   // --skip-bad, --max-bad
  std::string name;   // "filter", "smooth": the default output suffix and report prefix
  // A log whose estimates fail the trust check (solvers/trust_check.h) is an error, not only a
  // warning: RunEstimatorOverLogs then returns kUntrustedExit.
  bool strict = false;
  // --json: per log, the estimate file, the model, the trust check, the run's report and the
  // evaluation against truth.
  JsonOutput json;
  SuiteOptions suite;  // --jobs, --keep-going
  bool quiet = false;  // --quiet: no progress line
};

// Whether a run shows a progress line on stderr: a terminal, not --quiet, one log at a time.
bool ShowsProgress(const EstimatorRunOptions& run);

// The exit status of an estimator subcommand run with --strict when a log's estimates are not
// trusted (its outputs are still written).
constexpr int kUntrustedExit = 3;

// What an estimator gives for one log: its estimates and any columns of its own.
struct EstimatorOutput {
  std::vector<WardEstimate> estimates;
  std::vector<ExtraColumn> extra;
};

// `estimate` runs one log and writes its own report lines to `report`.
using Estimator = std::function<EstimatorOutput(const DriveLog& log, const ModelConfig& model,
                                                std::ostream& report)>;

// --skip-bad and --max-bad on a subcommand: how it reads its logs.
void AddReadOptions(CLI::App* cmd, ReadOptions* read);

// Reads a log for a subcommand, printing the reader's warnings (rows skipped, keys defaulted) and
// what CheckLogForEstimation finds (gaps, time coverage, frozen or stuck sensors, implausible
// values) to `warnings`; throws InputError where estimates would mean nothing.
DriveLog ReadLogWithWarnings(const std::string& path, const ReadOptions& read,
                             std::ostream& warnings = std::cerr);

// Registers an estimator subcommand with the flags they all share (LOG, --model, --no-gps,
// --skip-bad, --strict, --out, --json, --jobs, --keep-going, --quiet); the caller adds its own and
// sets the callback.
CLI::App* AddEstimatorCommand(CLI::App* app, const std::string& name,
                              const std::string& description, EstimatorRunOptions* run,
                              bool* no_gps);

// Returns the subcommand's exit status: 0; kFailedLogsExit when --keep-going ran past failed
// logs; else kUntrustedExit with options.strict when any log's estimates were not trusted. The
// estimator runs on --jobs logs at once: it may share nothing mutable between calls.
int RunEstimatorOverLogs(const EstimatorRunOptions& options, const Estimator& estimate);

// --solver chain|ceres: how the sliding window solves (online, compare).
void AddWindowSolverOption(CLI::App* cmd, WindowSolver* solver);

// The front end's variants (filter, online): --single-law, --no-gnss-fading,
// --disturbance-modes.
void AddFrontEndOptions(CLI::App* cmd, FilterRunOptions* filter);

// For a LOG argument: an empty path given (LOG "", a script's unset variable) is an error, not
// the bundled sample that no argument means.
CLI::Validator NonEmptyPath();

// --no-gnss-fading: *fading_fixes (EkfOptions::gnss_fading_fixes, the front end's) set to 0
// (filter, online, smooth, compare).
void AddNoGnssFadingFlag(CLI::App* cmd, double* fading_fixes);

// --stiffness-sd SD: the batch smoother's prior on the tire law's slip stiffness (smooth,
// compare); *prior_sd holds the default.
void AddStiffnessOption(CLI::App* cmd, double* prior_sd);

}  // namespace slipgraph
