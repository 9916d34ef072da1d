#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "apps/json_output.h"
#include "evaluation/evaluation.h"
#include "io/input_error.h"
#include "io/log_reader.h"

namespace slipgraph {
void RegisterEvaluateCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log;
    std::string estimates;
    JsonOutput json;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd =
      app->add_subcommand("evaluate", "Score estimates against the log's truth.csv and events.csv");
  cmd->add_option("LOG", options->log, "Log or suite directory")->check(NonEmptyPath())->required();
  cmd->add_option("ESTIMATES", options->estimates,
                  "Estimate CSV (a suite: the directory of <log>.csv files)")
      ->required();
  options->json.Add(cmd);
  cmd->callback([options, status]() {
    namespace fs = std::filesystem;
    const std::vector<std::string> logs = ListLogs(options->log);
    const bool suite = !IsLogDirectory(options->log);
    std::vector<Evaluation> runs;
    for (const std::string& log_dir : logs) {
      const std::string file =
          suite ? (fs::path(options->estimates) / (fs::path(log_dir).filename().string() + ".csv"))
                      .string()
                : options->estimates;
      runs.push_back(Evaluate(ReadDriveLog(log_dir), ReadNumericTable(file)));
      runs.back().name = log_dir;
    }
    const Evaluation total = suite ? Combine(runs, options->log) : runs.front();
    if (options->json.enabled()) {
      nlohmann::json out = ToJson(total);
      if (suite) {
        out["runs"] = nlohmann::json::array();
        for (const Evaluation& run : runs) out["runs"].push_back(ToJson(run));
      }
      options->json.Write(out);
    }
    std::ostream& text = options->json.text();
    if (suite) {
      for (const Evaluation& run : runs) PrintEvaluation(run, text);
      text << "total ";
    }
    PrintEvaluation(total, text);
    *status = 0;
  });
}

}  // namespace slipgraph
