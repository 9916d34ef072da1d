// Wilcox Fig. 4 on the simulated wilcox suite (40 runs: 0.25-4 cm RMS roughness, 20 % slip):
// odometry error of the total advance and front-sinkage RMSE per roughness, for an advance prior
// of 1 % and 10 % of the rim motion, baseline and factor graph on the same runs, and the
// left/right check on wilcox_lr. Prints a table (docs/wilcox.md).
// Run: build/bench/wilcox_report [--runs N]
//          [--method baseline|graph|graph_shared[_learned],...|all] [--roughness CM]
//          [--prior FRACTION] [--suite wilcox|wilcoxm|wilcox_slope] [--seed N] [--svg FILE]
// (N runs per roughness, default all 8; the graph takes about 8 s per run; graph_shared: both
// sides sharing the advance, WilcoxGraphOptions::shared_advance; *_learned: the prior learning
// its slip law from the paper's no-slip start, WilcoxOptions::learn_slip; --roughness 1 and
// --prior 0.1 keep one roughness and one prior; --method takes a comma-separated list; --svg
// writes the mean odometry error per method and prior against roughness as a plot).
// --suite wilcoxm: the same table on the mismatch suite (docs/mismatch.md).
// --suite wilcox_slope: the hill runs (slip 20 % + the slope), each method with the prior's
// slip law as the paper has it (0), constant at the true level (0.2), slope-dependent with the
// true law (0.2, 1) and learned from 0; odometry error and the largest error along the way.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "evaluation/html_report.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/wilcox_baseline.h"
#include "solvers/wilcox_graph.h"

namespace {

// One run by a method's name: baseline* or graph* (graph_shared*: the sides sharing the advance).
slipgraph::WilcoxResult Estimate(const std::string& method, const slipgraph::DriveLog& log,
                                 const slipgraph::WilcoxOptions& options, bool covariance) {
  if (method.rfind("baseline", 0) == 0) return slipgraph::EstimateWilcoxBaseline(log, options);
  slipgraph::WilcoxGraphOptions graph;
  graph.shared_advance = method.rfind("graph_shared", 0) == 0;
  graph.covariance = covariance;
  return slipgraph::EstimateWilcoxGraph(log, options, graph);
}

// A method name ending in _learned: the prior learns its slip law (WilcoxOptions::learn_slip).
bool Learns(const std::string& method) {
  const std::string suffix = "_learned";
  return method.size() > suffix.size() &&
         method.compare(method.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace slipgraph;  // NOLINT
  size_t runs_per_roughness = 1000;
  std::vector<std::string> methods = {"baseline",      "baseline_learned", "graph",
                                      "graph_learned", "graph_shared",     "graph_shared_learned"};
  std::string suite = "wilcox", only_roughness;
  uint64_t seed = 1;
  double only_prior = 0.0;
  std::string svg_path;  // Fig. 4 as a plot: mean odometry error per method and prior
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--runs") == 0) {
      runs_per_roughness = static_cast<size_t>(std::atoi(argv[i + 1]));
    } else if (std::strcmp(argv[i], "--roughness") == 0) {
      only_roughness = argv[i + 1];
    } else if (std::strcmp(argv[i], "--prior") == 0) {
      only_prior = std::atof(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--seed") == 0) {
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    } else if (std::strcmp(argv[i], "--suite") == 0) {
      suite = argv[i + 1];
    } else if (std::strcmp(argv[i], "--method") == 0) {
      if (std::strcmp(argv[i + 1], "all") != 0) {
        methods.clear();
        std::stringstream list(argv[i + 1]);
        for (std::string m; std::getline(list, m, ',');) methods.push_back(m);
      }
    } else if (std::strcmp(argv[i], "--svg") == 0) {
      svg_path = argv[i + 1];
    } else {
      std::fprintf(stderr,
                   "usage: wilcox_report [--runs N] [--method baseline|graph|graph_shared"
                   "[_learned]|all] [--roughness CM] [--prior FRACTION] "
                   "[--suite wilcox|wilcoxm|wilcox_slope] [--seed N] [--svg FILE]\n");
      return 2;
    }
  }
  if (suite == "wilcox_slope") {
    struct Law {
      const char* name;
      double slip, per_slope;
      bool learn;
    };
    const Law laws[] = {{"no slip (the paper)", 0.0, 0.0, false},
                        {"constant 0.2", 0.2, 0.0, false},
                        {"0.2 + slope (the truth)", 0.2, 1.0, false},
                        {"learned from 0", 0.0, 0.0, true}};
    std::map<std::string, std::vector<DriveLog>> logs_by_roughness;
    for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox_slope", seed)) {
      logs_by_roughness[run.relative_directory.substr(1, run.relative_directory.find("cm") - 1)]
          .push_back(sim::Simulate(run.scenario, run.seed).log);
    }
    std::printf(
        "| RMS roughness cm | runs | prior | method | prior's slip law | odometry error mean (max) "
        "| largest error along the way, mean mm | learned slip, per slope (left) |\n"
        "|---|---|---|---|---|---|---|---|\n");
    for (const auto& [roughness, logs] : logs_by_roughness) {
      if (!only_roughness.empty() && roughness != only_roughness) continue;
      for (double prior : {0.01, 0.1}) {
        if (only_prior > 0.0 && std::abs(prior - only_prior) > 1e-9) continue;
        for (const Law& law : laws) {
          WilcoxOptions options;
          options.prior_fraction = prior;
          options.prior_slip = law.slip;
          options.prior_slip_per_slope = law.per_slope;
          options.learn_slip = law.learn;
          for (const std::string& method : methods) {
            if (Learns(method)) continue;  // the laws say whether the prior learns
            double sum = 0.0, worst = 0.0, along = 0.0, slip = 0.0, per_slope = 0.0;
            for (const DriveLog& log : logs) {
              const WilcoxResult result = Estimate(method, log, options, false);
              const WilcoxScore score = ScoreWilcox(log, result);
              sum += score.odometry_error_fraction;
              worst = std::max(worst, score.odometry_error_fraction);
              along += score.max_position_error_m;
              slip += result.sides.at(0).law_slip;
              per_slope += result.sides.at(0).law_slip_per_slope;
            }
            const double n = static_cast<double>(logs.size());
            std::printf(
                "| %s | %zu | %.0f %% | %s | %s | %.2f %% (%.2f %%) | %.1f | %.3f, %.2f |\n",
                roughness.c_str(), logs.size(), 100.0 * prior, method.c_str(), law.name,
                100.0 * sum / n, 100.0 * worst, 1000.0 * along / n, slip / n, per_slope / n);
            std::fflush(stdout);
          }
        }
      }
    }
    return 0;
  }
  std::map<std::string, std::vector<DriveLog>> by_roughness;
  for (const sim::ScenarioRun& run : sim::ExpandScenario(suite, seed)) {
    const std::string roughness =
        run.relative_directory.substr(1, run.relative_directory.find("cm") - 1);
    if (!only_roughness.empty() && roughness != only_roughness) continue;
    std::vector<DriveLog>& logs = by_roughness[roughness];
    if (logs.size() < runs_per_roughness) logs.push_back(sim::Simulate(run.scenario, run.seed).log);
  }
  std::map<std::string, std::vector<std::pair<double, double>>> curves;
  std::printf(
      "| RMS roughness cm | runs | prior | method | odometry error mean (max) | rim motion alone | "
      "front sinkage RMSE mm | sides agree |\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& [roughness, logs] : by_roughness) {
    for (double prior : {0.01, 0.1}) {
      if (only_prior > 0.0 && std::abs(prior - only_prior) > 1e-9) continue;
      for (const std::string& method : methods) {
        WilcoxOptions options;
        options.prior_fraction = prior;
        options.learn_slip = Learns(method);
        double sum = 0.0, worst = 0.0, rim = 0.0, sinkage = 0.0;
        int agree = 0;
        for (const DriveLog& log : logs) {
          const WilcoxResult result = Estimate(method, log, options, true);
          const WilcoxScore score = ScoreWilcox(log, result);
          sum += score.odometry_error_fraction;
          worst = std::max(worst, score.odometry_error_fraction);
          rim += score.rim_odometry_error_fraction;
          sinkage += score.sinkage_rmse_m;
          agree += result.sides_agree;
        }
        const double n = static_cast<double>(logs.size());
        curves[method + " " + std::to_string(static_cast<int>(std::lround(100.0 * prior))) + " %"]
            .emplace_back(std::atof(roughness.c_str()), 100.0 * sum / n);
        std::printf("| %s | %zu | %.0f %% | %s | %.2f %% (%.2f %%) | %.1f %% | %.2f | %d/%zu |\n",
                    roughness.c_str(), logs.size(), 100.0 * prior, method.c_str(), 100.0 * sum / n,
                    100.0 * worst, 100.0 * rim / n, 1000.0 * sinkage / n, agree, logs.size());
        std::fflush(stdout);
      }
    }
  }
  if (!svg_path.empty()) {
    // Both axes logarithmic, as the values span 0.1-25 % over 0.25-4 cm.
    Plot plot;
    plot.title =
        "Wilcox Fig. 4, simulated wilcox suite (20 % slip): mean odometry error, prior 1 % "
        "(dashed) and 10 %";
    plot.x_label = "RMS roughness, log2 cm (-2: 0.25 cm, 0: 1 cm, 2: 4 cm)";
    plot.y_label = "odometry error, log10 % (0: 1 %)";
    const char* colors[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                            "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"};
    int c = 0;
    for (auto& [name, points] : curves) {
      std::sort(points.begin(), points.end());
      PlotSeries s = NewSeries(name, colors[c++ % 8], name.find(" 1 %") != std::string::npos);
      for (const auto& [roughness, error] : points) {
        s.t.push_back(std::log2(roughness));
        s.y.push_back(std::log10(std::max(error, 1e-3)));
      }
      plot.series.push_back(s);
    }
    for (const auto& [label, level] :
         {std::make_pair("1 % (the paper)", 1.0), std::make_pair("0.5 % (Ceres target)", 0.5)}) {
      PlotSeries s = NewSeries(label, "#000000", true);
      s.t = {-2.0, 2.0};
      s.y = {std::log10(level), std::log10(level)};
      plot.series.push_back(s);
    }
    std::ofstream out(svg_path);
    out << RenderSvg(plot, 900, 420);
    if (!out) {
      std::fprintf(stderr, "cannot write %s\n", svg_path.c_str());
      return 1;
    }
  }
  std::printf("\nwilcox_lr (2 cm, left sinks 1 cm more in soft patches on asym runs):\n\n");
  std::printf("| run | sides agree | check |\n|---|---|---|\n");
  for (const sim::ScenarioRun& run : sim::ExpandScenario("wilcox_lr", 1)) {
    const WilcoxResult result = EstimateWilcoxBaseline(sim::Simulate(run.scenario, run.seed).log);
    std::printf("| %s | %s | %s |\n", run.relative_directory.c_str(),
                result.sides_agree ? "yes" : "no", result.agreement.c_str());
  }
  return 0;
}
