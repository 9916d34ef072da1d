#include <iostream>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "io/log_reader.h"
#include "io/log_summary.h"

namespace slipgraph {

void RegisterInfoCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log;
    ReadOptions read;
  };
  auto options = std::make_shared<Options>();
  CLI::App* info = app->add_subcommand(
      "info", "Print a log's vehicle, streams, rates, duration, gaps and problems found");
  info->add_option("LOG", options->log, "Log directory (default: the bundled sample log)")
      ->check(NonEmptyPath());
  AddReadOptions(info, &options->read);
  info->callback([options, status]() {
    const std::string path = options->log.empty() ? DefaultLogPath() : options->log;
    const DriveLog log = ReadDriveLog(path, options->read);
    PrintLogSummary(log, SummarizeLog(log), std::cout);
    *status = 0;
  });
}

}  // namespace slipgraph
