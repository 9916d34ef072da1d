#include <iostream>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "io/log_reader.h"
#include "io/log_summary.h"

namespace slipgraph {

void RegisterInfoCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log;
    bool skip_bad = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* info = app->add_subcommand(
      "info", "Print a log's vehicle, streams, rates, duration, gaps and problems found");
  info->add_option("LOG", options->log, "Log directory (default: the bundled sample log)")
      ->check(NonEmptyPath());
  info->add_flag("--skip-bad", options->skip_bad,
                 "Drop bad rows and unusable optional files, with a warning each");
  info->callback([options, status]() {
    const std::string path = options->log.empty() ? DefaultLogPath() : options->log;
    ReadOptions read_options;
    read_options.skip_bad = options->skip_bad;
    const DriveLog log = ReadDriveLog(path, read_options);
    PrintLogSummary(log, SummarizeLog(log), std::cout);
    *status = 0;
  });
}

}  // namespace slipgraph
