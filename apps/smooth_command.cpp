#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "evaluation/evaluation.h"
#include "io/estimate_file.h"
#include "io/log_reader.h"
#include "io/yaml_config.h"
#include "solvers/batch_smoother.h"

namespace slipgraph {

void RegisterSmoothCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log;
    std::string model;
    bool no_gps = false;
    bool skip_bad = false;
    int threads = 1;
    std::string out;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "smooth", "Post-process a whole log with the Ceres batch smoother (EKF-initialised)");
  cmd->add_option("LOG", options->log, "Log or suite directory (default: the bundled sample)");
  cmd->add_option("--model", options->model, "Model YAML overriding the vehicle's nominal values");
  cmd->add_flag("--no-gps", options->no_gps, "Leave GNSS out");
  cmd->add_flag("--skip-bad", options->skip_bad, "Drop bad input rows, with a warning each");
  cmd->add_option("--threads", options->threads, "Solver threads")->check(CLI::PositiveNumber);
  cmd->add_option("--out", options->out,
                  "Estimate CSV (a suite: a directory, one CSV per log); default "
                  "./<log>_smooth.csv or ./<suite>_smooth/");
  cmd->callback([options, status]() {
    namespace fs = std::filesystem;
    const std::string path = options->log.empty() ? DefaultLogPath() : options->log;
    const std::vector<std::string> logs = ListLogs(path);
    const bool suite = !IsLogDirectory(path);
    const std::string name = fs::path(path).filename().string();
    std::string out = options->out;
    if (out.empty()) out = suite ? name + "_smooth" : name + "_smooth.csv";
    if (suite) fs::create_directories(out);
    BatchSmootherOptions smoother_options;
    smoother_options.filter.use_gps = !options->no_gps;
    smoother_options.threads = options->threads;
    ReadOptions read_options;
    read_options.skip_bad = options->skip_bad;
    for (const std::string& log_dir : logs) {
      const DriveLog log = ReadDriveLog(log_dir, read_options);
      for (const std::string& warning : log.warnings) std::cerr << "warning: " << warning << "\n";
      const ModelConfig model = options->model.empty()
                                    ? DefaultModelConfig(log.vehicle)
                                    : ReadModelYaml(options->model, log.vehicle);
      const SmootherResult result = SmoothBatch(log, model, smoother_options);
      const std::string file =
          suite ? (fs::path(out) / (fs::path(log_dir).filename().string() + ".csv")).string() : out;
      FilterResult as_rows;
      as_rows.estimates = result.estimates;
      WriteEkfEstimates(as_rows, file);
      std::cerr << "smooth: " << log_dir << " -> " << file << "\n" << DescribeSmootherRun(result);
      if (!log.truth.empty()) {
        const Evaluation ev = Evaluate(log, ReadNumericTable(file));
        std::cout << log_dir << " against truth: velocity RMSE " << ev.velocity_rmse
                  << " m/s, disturbance RMSE " << ev.disturbance_rmse << " m/s^2, immobilized "
                  << ev.detected() << "/" << ev.events.size() << " detected (mean delay "
                  << ev.mean_detection_delay_s() << " s), false immobilized "
                  << 100.0 * ev.false_immobilized_fraction() << " % of samples\n";
      }
    }
    *status = 0;
  });
}

}  // namespace slipgraph
