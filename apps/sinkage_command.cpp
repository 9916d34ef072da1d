// `slipgraph sinkage`: Wilcox's slippage and sinkage estimate for a 6-wheel articulated rover
// (the paper's histogram MAP algorithm, per side), with the left/right consistency check and,
// when the log has truth, the odometry error and sinkage RMSE.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/commands.h"
#include "apps/estimator_runs.h"
#include "apps/json_output.h"
#include "io/csv_writer.h"
#include "io/log_reader.h"
#include "solvers/wilcox_baseline.h"
#include "solvers/wilcox_graph.h"

namespace slipgraph {

void RegisterSinkageCommand(CLI::App* app, int* status) {
  struct Options {
    std::string log, out, method = "baseline";
    JsonOutput json;
    ReadOptions read;  // --skip-bad, --max-bad
    WilcoxOptions wilcox;
    WilcoxGraphOptions graph;
  };
  auto options = std::make_shared<Options>();
  // The prior learns its slip law by default here: on the simulated Fig. 4 suite its odometry
  // error is below the paper's fixed no-slip prior's in every row but one, where they tie (4 cm,
  // 10 %, graph), for both methods (docs/wilcox.md); --no-learn-slip gives the paper's algorithm.
  options->wilcox.learn_slip = true;
  CLI::App* cmd = app->add_subcommand(
      "sinkage",
      "Slippage and sinkage of an articulated rover from wheel-profile matching (Wilcox)");
  cmd->add_option("LOG", options->log, "rocker_bogie6 log with articulation.csv and range.csv")
      ->required();
  cmd->add_option("--out", options->out, "Directory for cycles.csv (default ./<log>_sinkage)");
  cmd->add_option("--method", options->method,
                  "baseline: the paper's histogram MAP; graph: the factor graph built cycle by "
                  "cycle on Ceres (slower, more accurate)")
      ->check(CLI::IsMember({"baseline", "graph"}))
      ->capture_default_str();
  cmd->add_flag("--shared-advance", options->graph.shared_advance,
                "graph: both sides in one problem sharing the rear wheels' positions (a rover "
                "driving straight); the left/right check then compares the sinkage");
  cmd->add_option("--prior", options->wilcox.prior_fraction,
                  "sd of the advance prior, as a fraction of the rim motion")
      ->capture_default_str();
  cmd->add_option("--prior-slip", options->wilcox.prior_slip,
                  "the advance prior's slip on level ground: its mean is the rim motion x (1 - "
                  "slip)")
      ->capture_default_str();
  cmd->add_option("--slip-per-slope", options->wilcox.prior_slip_per_slope,
                  "the prior's slip grows by this per unit of the slope the ranged points show "
                  "(uphill positive; 1: 10 % more slip on a 0.1 slope)")
      ->capture_default_str();
  cmd->add_flag("--learn-slip", options->wilcox.learn_slip,
                "Learn the prior's slip and slip per slope as the rover drives (the default), "
                "starting from --prior-slip and --slip-per-slope (from what the terrain matching "
                "measures on rough ground; the graph takes the law cycle by cycle as the baseline "
                "learns it)");
  cmd->add_flag_callback(
      "--no-learn-slip", [options] { options->wilcox.learn_slip = false; },
      "Keep the prior's slip and slip per slope fixed (the paper: slip 0)");
  cmd->add_option("--bin", options->wilcox.bin_m, "Histogram bin, m")->capture_default_str();
  options->json.Add(cmd);
  AddReadOptions(cmd, &options->read);
  cmd->callback([options, status]() {
    namespace fs = std::filesystem;
    const DriveLog log = ReadLogWithWarnings(options->log, options->read);
    const WilcoxResult result = options->method == "graph"
                                    ? EstimateWilcoxGraph(log, options->wilcox, options->graph)
                                    : EstimateWilcoxBaseline(log, options->wilcox);
    for (const std::string& note : result.notes) std::cerr << "note: " << note << "\n";
    const std::string out = options->out.empty()
                                ? fs::path(options->log).filename().string() + "_sinkage"
                                : options->out;
    fs::create_directories(out);
    {
      CsvWriter csv((fs::path(out) / "cycles.csv").string(),
                    {"t", "side", "rim_m", "advance_m", "slip", "sinkage_front_m", "sd_advance_m",
                     "sd_sinkage_front_m", "slope", "prior_slip"});
      for (const WilcoxSide& side : result.sides) {
        for (const WilcoxCycle& c : side.cycles) {
          csv << c.t << side.side << c.rim_m << c.advance_m
              << (c.rim_m > 0.0 ? 1.0 - c.advance_m / c.rim_m : 0.0) << c.sinkage_front_m
              << c.advance_sd_m << c.sinkage_front_sd_m << c.slope << c.prior_slip;
          csv.EndRow();
        }
      }
    }
    const bool truth = !log.truth.empty();
    const WilcoxScore score = ScoreWilcox(log, result);
    nlohmann::json j;
    j["method"] = options->method;
    j["sides_agree"] = result.sides_agree;
    j["agreement"] = result.agreement;
    for (const WilcoxSide& side : result.sides) {
      j["sides"][side.side] = {
          {"total_advance_m", side.total_advance_m},
          {"total_rim_m", side.total_rim_m},
          {"slip", side.total_rim_m > 0.0 ? 1.0 - side.total_advance_m / side.total_rim_m : 0.0},
          {"mean_sinkage_m", side.mean_sinkage_m},
          {"prior_slip", side.law_slip},
          {"prior_slip_per_slope", side.law_slip_per_slope},
          {"prior_slip_sd", side.law_slip_sd},
          {"prior_slip_per_slope_sd", side.law_slip_per_slope_sd},
          {"law_cycles_used", side.law_cycles_used}};
    }
    if (truth) {
      j["odometry_error_fraction"] = score.odometry_error_fraction;
      j["rim_odometry_error_fraction"] = score.rim_odometry_error_fraction;
      j["max_position_error_m"] = score.max_position_error_m;
      j["sinkage_rmse_m"] = score.sinkage_rmse_m;
    }
    j["cycles"] = (fs::path(out) / "cycles.csv").string();
    if (options->json.enabled()) {
      options->json.Write(j);
    }
    {
      std::FILE* text = options->json.text_file();
      for (const WilcoxSide& side : result.sides) {
        std::fprintf(
            text, "%s: advance %.4f m over rim %.4f m (slip %.1f %%), mean front sinkage %.1f mm\n",
            side.side.c_str(), side.total_advance_m, side.total_rim_m,
            side.total_rim_m > 0.0 ? 100.0 * (1.0 - side.total_advance_m / side.total_rim_m) : 0.0,
            1000.0 * side.mean_sinkage_m);
      }
      std::fprintf(text, "left/right: %s\n", result.agreement.c_str());
      if (truth) {
        std::fprintf(
            text,
            "against truth: odometry error %.2f %% (rim motion alone %.1f %%), at worst along "
            "the way %.1f mm, front sinkage RMSE %.2f mm\n",
            100.0 * score.odometry_error_fraction, 100.0 * score.rim_odometry_error_fraction,
            1000.0 * score.max_position_error_m, 1000.0 * score.sinkage_rmse_m);
      }
      std::fprintf(text, "per cycle: %s\n", (fs::path(out) / "cycles.csv").string().c_str());
    }
    *status = 0;
  });
}

}  // namespace slipgraph
