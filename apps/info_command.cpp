#include <iostream>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "apps/json_output.h"
#include "io/log_reader.h"
#include "io/log_summary.h"

namespace slipgraph {

void RegisterInfoCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log;
    ReadOptions read;
    JsonOutput json;
  };
  auto options = std::make_shared<Options>();
  CLI::App* info = app->add_subcommand(
      "info", "Print a log's vehicle, streams, rates, duration, gaps and problems found");
  info->add_option("LOG", options->log, "Log directory (default: the bundled sample log)")
      ->check(NonEmptyPath());
  AddReadOptions(info, &options->read);
  options->json.Add(info);
  info->callback([options, status]() {
    const std::string path = options->log.empty() ? DefaultLogPath() : options->log;
    const DriveLog log = ReadDriveLog(path, options->read);
    const LogSummary summary = SummarizeLog(log);
    PrintLogSummary(log, summary, options->json.text());
    if (options->json.enabled()) {
      nlohmann::json streams = nlohmann::json::array();
      for (const StreamSummary& s : summary.streams) {
        streams.push_back({{"name", s.name},
                           {"samples", s.samples},
                           {"t_first_s", s.t_first_s},
                           {"t_last_s", s.t_last_s},
                           {"rate_hz", s.rate_hz},
                           {"gaps", s.gaps}});
      }
      options->json.Write({{"log", path},
                           {"vehicle",
                            {{"name", log.vehicle.name},
                             {"type", VehicleTypeName(log.vehicle.type)},
                             {"wheels", WheelNames(log.vehicle.type)}}},
                           {"t_start_s", summary.t_start_s},
                           {"t_end_s", summary.t_end_s},
                           {"streams", streams},
                           {"reader_warnings", summary.reader_warnings},
                           {"problems", summary.problems},
                           {"plausibility", PlausibilityRecord(summary.plausibility)}});
    }
    *status = 0;
  });
}

}  // namespace slipgraph
