// `slipgraph import`: convert a recording (a ROS 1 bag, recognised by its header; a ROS 2 bag,
// a directory or a .db3 / .mcap file; or a MATLAB v7.3 file) into the drive-log format with a
// mapping file, then run the plausibility checks on the result (a wrong mapping shows as a
// physical impossibility).
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "apps/commands.h"
#include "apps/json_output.h"
#include "io/log_summary.h"
#include "io/log_writer.h"
#include "io/matlab_import.h"
#include "io/rosbag2_import.h"
#include "io/rosbag_import.h"
#include "io/yaml_config.h"

namespace slipgraph {

void RegisterImportCommand(CLI::App* app, int* status) {
  struct Options {
    std::string source, out, mapping, vehicle;
    bool list = false;
    JsonOutput json;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "import",
      "Convert a recording (a ROS 1 or ROS 2 bag, or MATLAB v7.3 / HDF5) into a drive log");
  cmd->add_option("SOURCE", options->source,
                  "The recording: a ROS 1 .bag; a ROS 2 bag directory, .db3 or .mcap file; a "
                  "MATLAB v7.3 .mat")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_flag("--list", options->list,
                "List the recording's topics (type, count, rate) or variables (dimensions) and "
                "stop: what a mapping file can name");
  cmd->add_option("--out", options->out, "Drive-log directory to write");
  cmd->add_option("--mapping", options->mapping,
                  "Mapping YAML: which variable is which stream, and the source's conventions "
                  "(see data/mappings/)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--vehicle", options->vehicle, "vehicle.yaml for the log")
      ->check(CLI::ExistingFile);
  options->json.Add(cmd);
  cmd->callback([options, status]() {
    if (options->list) {
      std::vector<std::string> notes;
      const bool bag = IsRosBag(options->source) || IsRos2Bag(options->source);
      const std::vector<SourceEntry> entries =
          IsRosBag(options->source)    ? ListRosBag(options->source)
          : IsRos2Bag(options->source) ? ListRos2Bag(options->source, &notes)
                                       : ListMatlab(options->source);
      for (const std::string& note : notes) std::cerr << "warning: " << note << "\n";
      std::ostream& text = options->json.text();
      nlohmann::json listed = nlohmann::json::array();
      for (const SourceEntry& e : entries) {
        text << e.name << "  " << e.type << "  " << e.count << (bag ? " messages" : " values")
             << (e.rate_hz > 0.0 ? ", " : "");
        if (e.rate_hz > 0.0) text << std::setprecision(3) << e.rate_hz << " Hz";
        text << "\n";
        listed.push_back({{"name", e.name},
                          {"type", e.type},
                          {bag ? "messages" : "values", e.count},
                          {"rate_hz", e.rate_hz > 0.0 ? nlohmann::json(e.rate_hz) : nullptr}});
      }
      if (options->json.enabled()) {
        options->json.Write({{"source", options->source}, {"entries", listed}, {"notes", notes}});
      }
      *status = 0;
      return;
    }
    if (options->out.empty() || options->mapping.empty() || options->vehicle.empty()) {
      std::cerr << "import: --out, --mapping and --vehicle are required (or --list)\n";
      *status = 106;
      return;
    }
    std::vector<std::string> warnings;
    const Vehicle vehicle = ReadVehicleYaml(options->vehicle, &warnings);
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
    ImportReport report;
    const std::string& source = options->source;
    DriveLog log = IsRosBag(source)    ? ImportRosBag(source, options->mapping, vehicle, &report)
                   : IsRos2Bag(source) ? ImportRos2Bag(source, options->mapping, vehicle, &report)
                                       : ImportMatlab(source, options->mapping, vehicle, &report);
    WriteDriveLog(log, options->out);
    std::ostream& text = options->json.text();
    text << "import: " << options->source << " -> " << options->out << "\n";
    for (const std::string& line : report.lines) text << "  " << line << "\n";
    log.directory = options->out;
    const LogSummary summary = SummarizeLog(log);
    const std::string checks = DescribePlausibility(summary.plausibility);
    if (!checks.empty()) text << "checks: " << checks << "\n";
    if (summary.problems.empty()) {
      text << "plausibility: no problems found\n";
    } else {
      text << "plausibility: " << summary.problems.size() << " problem(s)\n";
      for (const std::string& p : summary.problems) text << "  - " << p << "\n";
    }
    if (options->json.enabled()) {
      options->json.Write({{"source", options->source},
                           {"log", options->out},
                           {"files", log.present_files},
                           {"report", report.lines},
                           {"warnings", warnings},
                           {"problems", summary.problems},
                           {"plausibility", PlausibilityRecord(summary.plausibility)}});
    }
    *status = 0;
  });
}

}  // namespace slipgraph
