// `slipgraph compare`: the EKF front end, the sliding-window smoother and the batch smoother on
// the same log(s), side by side against truth: a table on the terminal and a self-contained HTML
// page with the estimates over time.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "apps/commands.h"
#include "apps/estimate_plots.h"
#include "apps/estimator_runs.h"
#include "apps/json_output.h"
#include "evaluation/evaluation.h"
#include "evaluation/html_report.h"
#include "io/log_reader.h"
#include "io/yaml_config.h"
#include "solvers/batch_smoother.h"
#include "solvers/trust_check.h"
#include "solvers/window_smoother.h"

namespace slipgraph {
namespace {

using Clock = std::chrono::steady_clock;

struct EstimatorRun {
  std::string name;
  std::vector<WardEstimate> estimates;
  double seconds = 0.0;
  std::string report;
};

std::string Format(const char* format, double value) {
  if (!std::isfinite(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

// untrusted / logs: how many of the logs the trust check (solvers/trust_check.h) failed.
std::vector<std::string> Row(const std::string& name, const Evaluation& ev, double seconds,
                             int untrusted, int logs) {
  return {name,
          Format("%.4f", ev.velocity_rmse),
          Format("%.3f", ev.disturbance_rmse),
          std::to_string(ev.detected()) + "/" + std::to_string(ev.events.size()),
          Format("%.3f", ev.mean_detection_delay_s()),
          Format("%.3f", 100.0 * ev.false_immobilized_fraction()),
          Format("%.2f", ev.velocity_mean_nees),
          Format("%.1f", 100.0 * ev.nees_within_95_fraction()),
          Format("%.2f", seconds),
          logs == 1 ? (untrusted == 0 ? "yes" : "NO")
                    : std::to_string(logs - untrusted) + "/" + std::to_string(logs)};
}

const std::vector<std::string> kHeader = {
    "estimator",           "v RMSE m/s",  "a_dist RMSE m/s^2",    "detected", "mean delay s",
    "false immobilized %", "v NEES mean", "NEES within 95 % (%)", "time s",   "trusted"};

void PrintTable(const std::vector<std::vector<std::string>>& rows, std::ostream& out) {
  out << "|";
  for (const std::string& h : kHeader) out << " " << h << " |";
  out << "\n|";
  for (size_t i = 0; i < kHeader.size(); ++i) out << "---|";
  out << "\n";
  for (const auto& row : rows) {
    out << "|";
    for (const std::string& cell : row) out << " " << cell << " |";
    out << "\n";
  }
}

const char* kColors[] = {"#d62728", "#2ca02c", "#1f77b4"};  // EKF, window, batch

}  // namespace

void RegisterCompareCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log, model, html;
    bool no_gps = false, no_plots = false;
    ReadOptions read;  // --skip-bad, --max-bad
    WindowSmootherOptions window;
    double stiffness_sd = std::nan("");                         // PostProcessingStiffnessPriorSd
    double gnss_fading_fixes = EkfOptions().gnss_fading_fixes;  // the front end's
    JsonOutput json;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app->add_subcommand(
      "compare", "EKF vs sliding-window smoother vs batch smoother (vs truth): table and HTML");
  cmd->add_option("LOG", options->log, "Log or suite directory (default: the bundled sample)")
      ->check(NonEmptyPath());
  cmd->add_option("--model", options->model, "Model YAML overriding the vehicle's nominal values");
  cmd->add_flag("--no-gps", options->no_gps, "Leave GNSS out");
  AddReadOptions(cmd, &options->read);
  cmd->add_option("--window", options->window.window_s, "Window length, s")->capture_default_str();
  AddWindowSolverOption(cmd, &options->window.solver);
  cmd->add_option("--report,--html", options->html,
                  "Report page (default ./<log>_compare.html); plots of every log in it");
  cmd->add_flag("--no-plots", options->no_plots, "Tables only in the HTML page");
  AddStiffnessOption(cmd, &options->stiffness_sd);
  AddNoGnssFadingFlag(cmd, &options->gnss_fading_fixes);
  options->json.Add(cmd);
  cmd->callback([options, status]() {
    namespace fs = std::filesystem;
    const std::string path = options->log.empty() ? DefaultLogPath() : options->log;
    const std::string name = fs::path(path).filename().string();
    const std::string html_path = options->html.empty() ? name + "_compare.html" : options->html;
    HtmlReport html("slipgraph compare: " + name);
    std::map<std::string, std::vector<Evaluation>> by_estimator;
    std::map<std::string, double> seconds;
    std::map<std::string, int> untrusted;  // logs the trust check failed, per estimator
    // Logs with truth whose batch estimated the slip stiffness, with this prior.
    int stiffness_logs = 0;
    double stiffness_prior_sd = 0.0;
    const std::vector<std::string> names = {"EKF", "window", "batch"};
    nlohmann::json logs_json = nlohmann::json::array();
    for (const std::string& log_dir : ListLogs(path)) {
      DriveLog log = ReadLogWithWarnings(log_dir, options->read);
      const ModelConfig model = ModelForLog(&log, options->model);
      std::vector<EstimatorRun> runs(3);
      FilterRunOptions filter;
      filter.use_gps = !options->no_gps;
      filter.ekf.gnss_fading_fixes = options->gnss_fading_fixes;
      Clock::time_point start = Clock::now();
      const FilterResult ekf = RunEkf(log, model, filter);
      // One front end run: the window and the batch start from it; their times include it.
      const double ekf_s = std::chrono::duration<double>(Clock::now() - start).count();
      runs[0] = {"EKF", ekf.estimates, ekf_s, DescribeFilterRun(ekf)};
      WindowSmootherOptions window = options->window;
      window.filter = filter;
      start = Clock::now();
      const WindowSmootherResult windowed = SmoothWindowed(log, model, ekf, window);
      runs[1] = {"window", windowed.estimates,
                 ekf_s + std::chrono::duration<double>(Clock::now() - start).count(),
                 DescribeWindowRun(windowed)};
      BatchSmootherOptions batch;
      batch.filter = filter;
      batch.problem.stiffness_prior_sd =
          PostProcessingStiffnessPriorSd(model, options->stiffness_sd);
      if (batch.problem.stiffness_prior_sd > 0.0 && !log.truth.empty()) {
        ++stiffness_logs;
        stiffness_prior_sd = batch.problem.stiffness_prior_sd;
      }
      start = Clock::now();
      const SmootherResult smoothed = SmoothBatch(log, model, ekf, batch);
      runs[2] = {"batch", smoothed.estimates,
                 ekf_s + std::chrono::duration<double>(Clock::now() - start).count(),
                 DescribeSmootherRun(smoothed)};
      std::cerr << "compare: " << log_dir << "\n";
      html.Heading(log_dir, 2);
      nlohmann::json log_json = {{"log", log_dir},
                                 {"model", ModelRecord(options->model, model)},
                                 {"runs", nlohmann::json::array()}};
      for (const EstimatorRun& run : runs) {
        log_json["runs"].push_back({{"estimator", run.name},
                                    {"seconds", run.seconds},
                                    {"trusted", CheckTrust(log, run.estimates).trusted},
                                    {"evaluation", nullptr}});
      }
      if (!log.truth.empty()) {
        std::vector<std::vector<std::string>> rows;
        for (size_t r = 0; r < runs.size(); ++r) {
          const EstimatorRun& run = runs[r];
          const Evaluation ev = Evaluate(log, EstimateTable(run.estimates));
          by_estimator[run.name].push_back(ev);
          seconds[run.name] += run.seconds;
          const bool trusted = log_json["runs"][r]["trusted"].get<bool>();
          untrusted[run.name] += trusted ? 0 : 1;
          rows.push_back(Row(run.name, ev, run.seconds, trusted ? 0 : 1, 1));
          log_json["runs"][r]["evaluation"] = ToJson(ev);
        }
        html.Table(kHeader, rows);
      } else {
        html.Paragraph("No truth.csv: the estimates are compared with each other only.");
      }
      html.Preformatted(runs[1].report + runs[2].report);
      if (!options->no_plots) {
        std::vector<NamedEstimates> plotted;
        for (size_t r = 0; r < runs.size(); ++r) {
          plotted.push_back({runs[r].name, &runs[r].estimates, kColors[r % 3]});
        }
        AddEstimatePlots(log, plotted, &html);
      }
      logs_json.push_back(log_json);
    }
    std::ostream& text = options->json.text();
    nlohmann::json out = {{"logs", logs_json}, {"report", html_path}};
    if (!by_estimator.empty()) {
      std::vector<std::vector<std::string>> rows;
      out["total"] = nlohmann::json::array();
      for (const std::string& estimator : names) {
        const Evaluation total = Combine(by_estimator[estimator], name);
        rows.push_back(Row(estimator, total, seconds[estimator], untrusted[estimator],
                           static_cast<int>(by_estimator[estimator].size())));
        out["total"].push_back({{"estimator", estimator},
                                {"seconds", seconds[estimator]},
                                {"untrusted_logs", untrusted[estimator]},
                                {"evaluation", ToJson(total)}});
      }
      char prior[96];
      std::snprintf(prior, sizeof(prior), " on %d of %zu log(s) (prior sd %g", stiffness_logs,
                    by_estimator["EKF"].size(), stiffness_prior_sd);
      const std::string batch_law =
          stiffness_logs > 0
              ? std::string("the batch estimates the tire law's slip stiffness") + prior +
                    ", kept where GNSS does not favour the law as given; by default where the "
                    "model lists its soils; --stiffness-sd 0: the law as given)"
              : "the batch keeps the tire law as given";
      text << name << " (" << by_estimator["EKF"].size()
           << " log(s)) against truth; window and batch times include the EKF run they start "
              "from; trusted: the estimates hold against the log's own wheels and GNSS; "
           << batch_law << "\n";
      PrintTable(rows, text);
      HtmlReport summary = html;  // the summary goes first on the page
      HtmlReport page("slipgraph compare: " + name);
      page.Heading("All logs", 2);
      page.Paragraph(std::to_string(by_estimator["EKF"].size()) +
                     " log(s). Window and batch times include the EKF run they start from. "
                     "Trusted: the estimates hold against the log's own wheels and GNSS "
                     "(solvers/trust_check.h). The window "
                     "smoother's estimates are each state's value as it left the window "
                     "(lag = window length). The window keeps the tire law as given; " +
                     batch_law + ".");
      page.Table(kHeader, rows);
      page.Append(summary);
      page.Paragraph(options->json.RecordText());
      page.Write(html_path);
    } else {
      text << name << ": no truth in the log(s); see the plots\n";
      html.Paragraph(options->json.RecordText());
      html.Write(html_path);
    }
    text << "report: " << html_path << "\n";
    if (options->json.enabled()) options->json.Write(out);
    *status = 0;
  });
}

}  // namespace slipgraph
