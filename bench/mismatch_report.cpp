// The estimators on a matched suite and its mismatch twin (docs/mismatch.md), seed by seed:
// detection, false alarms, velocity error and consistency of the front end with and without
// GNSS, with --window of the online window behind it, and with --smoother of the batch smoother.
// Simulates each suite in memory.
//
// Run: build/bench/mismatch_report [--suite ward21m] [--seeds A-B] [--window] [--smoother]
//        [--threads N]
//   --suite: ward21 or ward21m (default ward21m);
//   --seeds: the suites' seeds (default 1-4);
//   --window: add the online window (GNSS; `online`'s defaults) behind the EKF's run, and its
//     velocity RMSE over the EKF's run by run;
//   --reject-distance SD: the window's rejection of a solve far from the front end
//     (WindowSmootherOptions::reject_distance_sd; 0: never), for choosing it on other seeds;
//   --no-pull-back SD: the smoothers' weak constraint 3 on the velocity at this density
//     (WardProblemOptions::no_pull_back_sd_density; 0: off), for choosing it on other seeds;
//   --model-disturbance: the window's disturbance walk at the model's w3, not the front end's
//     adaptive one (WindowSmootherOptions::disturbance_from_front_end = false);
//   --no-bias-checks: the smoothers without the front end's wheels' checks on its accelerometer
//     bias (bias_from_front_end = false), for comparing;
//   --law-correlation S: the smoothers' correlation time of the tire law's error
//     (WardProblemOptions::tire_law_correlation_time_s), for choosing it on other seeds;
//   --smoother: add the batch smoother (GNSS; a few seconds per run);
//   --threads: suites run at once (default 2);
//   --without A,B: mismatch ingredients restored to the matched suite's (soils, attitude,
//     vibration, gnss, radius, relaxation): an ablation;
//   --fading-fixes N, --fading-threshold T: the front end's GNSS fading memory (EkfOptions; by
//     default on, as `filter` runs it; N = 0: off, as `filter --no-gnss-fading`), for choosing
//     them on seeds the figures are not reported on;
//   --disturbance-modes: the single filter as disturbance modes (solvers/disturbance_imm.h);
//     --imm-options TAU,SD,HELD,TQ,TC,TH[,MIX] sets its options (DisturbanceImmOptions, in that
//     order), for choosing them on seeds the figures are not reported on;
//   --single-law: one filter also where vehicle.yaml lists law samples;
//   --stiffness-sd SD, --stiffness-margin M: the batch's slip-stiffness prior (0: the law as
//     given; default: `smooth`'s, PostProcessingStiffnessPriorSd) and its check against GNSS
//     (BatchSmootherOptions::stiffness_gnss_margin; inf: none);
//   --window-stiffness-sd SD: the window's slip-stiffness prior (WindowSmootherOptions::
//     stiffness_prior_sd; 0: the law as given);
//   --window-length S: with --window, the window's span in seconds (WindowSmootherOptions::
//     window_s; `online --window S`);
//   --runs: list each run with false alarms (seed, run, estimator, samples, v RMSE) or missed
//     hold-backs;
//   --model FILE: a model file (the `--model` of the subcommands) over each log's defaults, for
//     trying a setting on seeds the figures are not reported on.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "evaluation/evaluation.h"
#include "io/text_file.h"
#include "io/yaml_config.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/batch_smoother.h"
#include "solvers/ekf_runner.h"
#include "solvers/run_concurrently.h"
#include "solvers/trust_check.h"
#include "solvers/window_smoother.h"

namespace slipgraph {
namespace {

enum Estimator { kEkfGnss = 0, kEkfNoGnss, kWindowGnss, kBatchGnss, kEstimatorCount };
const char* const kNames[kEstimatorCount] = {"EKF, GNSS", "EKF, no GNSS", "window, GNSS",
                                             "batch, GNSS"};

struct SuiteResult {
  Evaluation evaluation[kEstimatorCount];
  // The runs the trust check (solvers/trust_check.h) passed, pooled, and how many it did not.
  Evaluation trusted[kEstimatorCount];
  int untrusted_runs[kEstimatorCount] = {};
  int smoother_fallbacks = 0;
  // --window: per run, the window's velocity RMSE over the EKF's (GNSS), and the window's
  // updates that were rejected or fell back.
  std::vector<double> window_ratio;
  std::vector<std::string> window_above;  // "run: EKF v RMSE, window's" where the ratio > 1.05
  long window_failed_updates = 0, window_rejected_updates = 0, window_updates = 0;
  long window_more_false = 0;  // runs where the window flags more false samples than the EKF
  // --runs: per run with false alarms, "seed run estimator: false samples, v RMSE", and per run
  // with missed hold-backs, "seed run estimator: N of M hold-backs missed".
  std::vector<std::string> listed_runs;
};

// --without: the mismatch ingredients taken back out of a mismatch suite's scenarios, each
// restored to the matched suite's (an ablation: which ingredient costs what).
std::vector<std::string> g_without;
// The front end as the flags set it, for the EKF runs and behind the window and the smoother:
// --fading-fixes, --fading-threshold (EkfOptions' GNSS fading memory), --single-law,
// --disturbance-modes and --imm-options.
FilterRunOptions g_front;
// --stiffness-sd, --stiffness-margin: the batch's slip stiffness prior and its GNSS check
// (as `smooth` and `compare` run them by default).
double g_stiffness_sd = std::nan("");  // PostProcessingStiffnessPriorSd
double g_stiffness_gnss_margin = BatchSmootherOptions{}.stiffness_gnss_margin;
// --window-stiffness-sd: the window's slip stiffness prior.
double g_window_stiffness_sd = WindowSmootherOptions{}.stiffness_prior_sd;
// --window-length: the window's span (with --window).
double g_window_s = WindowSmootherOptions{}.window_s;
// --runs: list the runs with false alarms.
bool g_list_runs = false;
double g_reject_distance_sd = WindowSmootherOptions{}.reject_distance_sd;
// --no-pull-back: NaN keeps each smoother's default (the window's on, the batch's off).
double g_no_pull_back_sd = std::nan("");
bool g_disturbance_from_front_end = WindowSmootherOptions{}.disturbance_from_front_end;
bool g_bias_from_front_end = true;  // --no-bias-checks: false
double g_law_correlation_s = WardProblemOptions{}.tire_law_correlation_time_s;
// --model: the model file's path and text, applied over each log's vehicle (empty: defaults).
std::string g_model_path, g_model_text;

bool Without(const std::string& ingredient) {
  return std::find(g_without.begin(), g_without.end(), ingredient) != g_without.end();
}

sim::Scenario Ablate(sim::Scenario sc, const sim::Scenario& matched) {
  if (Without("soils")) {  // the matched soils and the user's stated law_samples
    sc.course.patches = matched.course.patches;
    sc.vehicle = matched.vehicle;
  }
  if (Without("attitude")) {
    sc.sensors.attitude_sd_rad = matched.sensors.attitude_sd_rad;
    sc.sensors.mismatch.attitude_error_sd_rad = 0.0;
  }
  if (Without("vibration")) sc.sensors.mismatch.vibration_sd_mps2_per_mps = 0.0;
  if (Without("gnss")) sc.sensors.mismatch.gps_velocity_interval_mean = false;
  if (Without("radius")) sc.mismatch.radius_load_sensitivity = 0.0;
  if (Without("relaxation")) sc.mismatch.relaxation_length_m = 1e-3;
  return sc;
}

SuiteResult RunSuite(const std::string& suite, uint64_t seed, bool window, bool smoother) {
  SuiteResult out;
  std::vector<Evaluation> runs[kEstimatorCount], trusted_runs[kEstimatorCount];
  std::string run_name;
  const auto score = [&](int e, const DriveLog& log, const std::vector<WardEstimate>& estimates) {
    runs[e].push_back(Evaluate(log, EstimateTable(estimates)));
    const Evaluation& ev = runs[e].back();
    if (g_list_runs && ev.false_immobilized_samples > 0) {
      char line[200];
      std::snprintf(line, sizeof(line), "seed %llu %s %s: %ld false samples (%.2f %%), v RMSE %.4f",
                    static_cast<unsigned long long>(seed), run_name.c_str(), kNames[e],
                    ev.false_immobilized_samples, 100.0 * ev.false_immobilized_fraction(),
                    ev.velocity_rmse);
      out.listed_runs.push_back(line);
    }
    if (g_list_runs && ev.detected() < static_cast<int>(ev.events.size())) {
      char line[200];
      std::snprintf(line, sizeof(line), "seed %llu %s %s: %d of %zu hold-backs missed",
                    static_cast<unsigned long long>(seed), run_name.c_str(), kNames[e],
                    static_cast<int>(ev.events.size()) - ev.detected(), ev.events.size());
      out.listed_runs.push_back(line);
    }
    if (CheckTrust(log, estimates).trusted) {
      trusted_runs[e].push_back(runs[e].back());
    } else {
      ++out.untrusted_runs[e];
    }
  };
  const std::vector<sim::ScenarioRun> scenario_runs = sim::ExpandScenario(suite, seed);
  std::vector<sim::ScenarioRun> matched;
  if (!g_without.empty()) {
    std::string name = suite;
    name.erase(name.find('m'), 1);  // ward21m -> ward21
    matched = sim::ExpandScenario(name, seed);
  }
  for (size_t r = 0; r < scenario_runs.size(); ++r) {
    const sim::ScenarioRun& run = scenario_runs[r];
    const sim::Scenario scenario =
        matched.empty() ? run.scenario : Ablate(run.scenario, matched[r].scenario);
    const DriveLog log = sim::Simulate(scenario, run.seed).log;
    run_name = run.relative_directory;
    const ModelConfig model = g_model_path.empty()
                                  ? DefaultModelConfig(log.vehicle)
                                  : ParseModelYaml(g_model_path, g_model_text, log.vehicle);
    FilterResult with_gnss;
    for (int e = kEkfGnss; e <= kEkfNoGnss; ++e) {
      FilterRunOptions options = g_front;
      options.use_gps = e == kEkfGnss;
      FilterResult result = RunEkf(log, model, options);
      score(e, log, result.estimates);
      if (e == kEkfGnss) with_gnss = std::move(result);
    }
    if (window) {
      WindowSmootherOptions options;
      options.filter = g_front;
      options.reject_distance_sd = g_reject_distance_sd;
      options.stiffness_prior_sd = g_window_stiffness_sd;
      options.window_s = g_window_s;
      if (!std::isnan(g_no_pull_back_sd)) options.no_pull_back_sd_density = g_no_pull_back_sd;
      options.disturbance_from_front_end = g_disturbance_from_front_end;
      options.bias_from_front_end = g_bias_from_front_end;
      options.problem.tire_law_correlation_time_s = g_law_correlation_s;
      const WindowSmootherResult result = SmoothWindowed(log, model, std::move(with_gnss), options);
      out.window_failed_updates += result.failed_updates;
      out.window_rejected_updates += result.rejected_updates;
      out.window_updates += result.updates;
      score(kWindowGnss, log, result.estimates);
      const double ekf = runs[kEkfGnss].back().velocity_rmse;
      const double refined = runs[kWindowGnss].back().velocity_rmse;
      out.window_ratio.push_back(refined / ekf);
      out.window_more_false += runs[kWindowGnss].back().false_immobilized_samples >
                               runs[kEkfGnss].back().false_immobilized_samples;
      if (refined > 1.05 * ekf) {
        char line[160];
        std::snprintf(line, sizeof(line), "seed %llu %s: EKF %.4f, window %.4f m/s (%.2f x)",
                      static_cast<unsigned long long>(seed), run.relative_directory.c_str(), ekf,
                      refined, refined / ekf);
        out.window_above.push_back(line);
      }
    }
    if (smoother) {
      BatchSmootherOptions options;
      options.filter = g_front;
      options.problem.stiffness_prior_sd = PostProcessingStiffnessPriorSd(model, g_stiffness_sd);
      if (!std::isnan(g_no_pull_back_sd))
        options.problem.no_pull_back_sd_density = g_no_pull_back_sd;
      options.stiffness_gnss_margin = g_stiffness_gnss_margin;
      options.bias_from_front_end = g_bias_from_front_end;
      options.problem.tire_law_correlation_time_s = g_law_correlation_s;
      const SmootherResult result = SmoothBatch(log, model, options);
      out.smoother_fallbacks += result.used_fallback ? 1 : 0;
      score(kBatchGnss, log, result.estimates);
    }
  }
  for (int e = 0; e < kEstimatorCount; ++e) {
    if (!runs[e].empty()) out.evaluation[e] = Combine(runs[e], suite);
    out.trusted[e] = Combine(trusted_runs[e], suite);
  }
  return out;
}

void PrintCells(const Evaluation& ev) {
  std::printf(" %d/%zu | %.2f | %.3f | %.4f | %.0f |", ev.detected(), ev.events.size(),
              ev.mean_detection_delay_s(), 100.0 * ev.false_immobilized_fraction(),
              ev.velocity_rmse, 100.0 * ev.nees_within_95_fraction());
}

}  // namespace
}  // namespace slipgraph

int main(int argc, char** argv) {
  using namespace slipgraph;  // NOLINT
  std::string suite = "ward21m";
  uint64_t first = 1, last = 4;
  bool smoother = false, window = false;
  int threads = 2;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--suite") == 0 && has_value)
      suite = argv[++i];
    else if (std::strcmp(argv[i], "--seeds") == 0 && has_value) {
      char* end = nullptr;
      first = std::strtoull(argv[++i], &end, 10);
      last = *end == '-' ? std::strtoull(end + 1, nullptr, 10) : first;
    } else if (std::strcmp(argv[i], "--threads") == 0 && has_value) {
      threads = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--without") == 0 && has_value) {
      std::string list = argv[++i];
      for (size_t start = 0; start <= list.size();) {
        const size_t comma = std::min(list.find(',', start), list.size());
        g_without.push_back(list.substr(start, comma - start));
        start = comma + 1;
      }
    } else if (std::strcmp(argv[i], "--fading-fixes") == 0 && has_value) {
      g_front.ekf.gnss_fading_fixes = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--fading-threshold") == 0 && has_value) {
      g_front.ekf.gnss_fading_threshold = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--single-law") == 0) {
      g_front.multiple_model = false;
    } else if (std::strcmp(argv[i], "--disturbance-modes") == 0) {
      g_front.disturbance_modes = true;
    } else if (std::strcmp(argv[i], "--imm-options") == 0 && has_value) {
      DisturbanceImmOptions& o = g_front.disturbance_modes_options;
      g_front.disturbance_modes =
          std::sscanf(argv[++i], "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &o.quiet_a_dist_tau_s,
                      &o.quiet_a_dist_sd_mps2, &o.held_a_dist_mps3_per_sqrt_hz, &o.quiet_mean_s,
                      &o.change_mean_s, &o.held_mean_s, &o.mix_interval_s) >= 6;
    } else if (std::strcmp(argv[i], "--window-stiffness-sd") == 0 && has_value) {
      g_window_stiffness_sd = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--window-length") == 0 && has_value) {
      g_window_s = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--stiffness-sd") == 0 && has_value) {
      g_stiffness_sd = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--stiffness-margin") == 0 && has_value) {
      g_stiffness_gnss_margin = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--model") == 0 && has_value) {
      g_model_path = argv[++i];
      g_model_text = ReadTextFile(g_model_path);
    } else if (std::strcmp(argv[i], "--window") == 0) {
      window = true;
    } else if (std::strcmp(argv[i], "--no-pull-back") == 0 && has_value) {
      g_no_pull_back_sd = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--model-disturbance") == 0) {
      g_disturbance_from_front_end = false;
    } else if (std::strcmp(argv[i], "--no-bias-checks") == 0) {
      g_bias_from_front_end = false;
    } else if (std::strcmp(argv[i], "--law-correlation") == 0 && has_value) {
      g_law_correlation_s = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--reject-distance") == 0 && has_value) {
      g_reject_distance_sd = std::atof(argv[++i]);
    } else if (std::strcmp(argv[i], "--smoother") == 0) {
      smoother = true;
    } else if (std::strcmp(argv[i], "--runs") == 0) {
      g_list_runs = true;
    } else {
      std::fprintf(stderr, "mismatch_report: unknown argument '%s'\n", argv[i]);
      return 2;
    }
  }
  if (first == 0 || last < first || threads < 1) {
    std::fprintf(stderr, "mismatch_report: --seeds A-B with 1 <= A <= B, --threads >= 1\n");
    return 2;
  }
  const size_t count = static_cast<size_t>(last - first + 1);
  std::vector<SuiteResult> results(count);
  RunConcurrently(count, threads,
                  [&](size_t i) { results[i] = RunSuite(suite, first + i, window, smoother); });

  std::vector<int> shown = {kEkfGnss, kEkfNoGnss};
  if (window) shown.push_back(kWindowGnss);
  if (smoother) shown.push_back(kBatchGnss);
  std::printf(
      "%s, seeds %llu-%llu: per estimator detected / events, mean delay s, false "
      "immobilized %%, v RMSE m/s, v NEES inside its 95 %% bound %%\n\n",
      suite.c_str(), static_cast<unsigned long long>(first), static_cast<unsigned long long>(last));
  std::printf("| seed |");
  for (int e : shown) std::printf(" %s: det. | delay | false %% | v RMSE | NEES %% |", kNames[e]);
  std::printf("\n|---|");
  for (size_t e = 0; e < shown.size(); ++e) std::printf("---|---|---|---|---|");
  std::printf("\n");
  for (size_t i = 0; i < count; ++i) {
    std::printf("| %llu |", static_cast<unsigned long long>(first + i));
    for (int e : shown) PrintCells(results[i].evaluation[e]);
    std::printf("\n");
  }
  std::printf("\n");
  for (int e : shown) {
    std::vector<Evaluation> all;
    double false_mean = 0.0, worst = 0.0;
    for (const SuiteResult& r : results) {
      all.push_back(r.evaluation[e]);
      false_mean += r.evaluation[e].false_immobilized_fraction() / count;
      worst = std::max(worst, r.evaluation[e].false_immobilized_fraction());
    }
    const Evaluation pooled = Combine(all, suite);
    std::printf(
        "%s: %d/%zu detected, mean delay %.2f s, false immobilized %.3f %% (mean over "
        "suites; worst suite %.3f %%), v RMSE %.4f m/s, v NEES inside 95 %% %.2f %%\n",
        kNames[e], pooled.detected(), pooled.events.size(), pooled.mean_detection_delay_s(),
        100.0 * false_mean, 100.0 * worst, pooled.velocity_rmse,
        100.0 * pooled.nees_within_95_fraction());
    std::vector<Evaluation> trusted;
    int untrusted = 0;
    for (const SuiteResult& r : results) {
      trusted.push_back(r.trusted[e]);
      untrusted += r.untrusted_runs[e];
    }
    const Evaluation t = Combine(trusted, suite);
    std::printf(
        "  trust check: %d runs untrusted; the trusted runs: false immobilized %.3f %% of "
        "samples, v RMSE %.4f m/s, v NEES inside 95 %% %.1f %%\n",
        untrusted, 100.0 * t.false_immobilized_fraction(), t.velocity_rmse,
        100.0 * t.nees_within_95_fraction());
  }
  if (window) {
    std::vector<double> ratios;
    long failed = 0, rejected = 0, updates = 0, more_false = 0;
    for (const SuiteResult& r : results) {
      ratios.insert(ratios.end(), r.window_ratio.begin(), r.window_ratio.end());
      failed += r.window_failed_updates;
      rejected += r.window_rejected_updates;
      updates += r.window_updates;
      more_false += r.window_more_false;
    }
    double mean = 0.0;
    for (double ratio : ratios) mean += ratio / ratios.size();
    const double worst = ratios.empty() ? 0.0 : *std::max_element(ratios.begin(), ratios.end());
    const long above =
        std::count_if(ratios.begin(), ratios.end(), [](double r) { return r > 1.05; });
    std::printf(
        "window v RMSE over the EKF's, run by run: mean %.3f, worst %.3f, above 1.05 on %ld of "
        "%zu runs; of %ld window updates %ld failed, %ld rejected; more false immobilized "
        "samples than the EKF on %ld runs\n",
        mean, worst, above, ratios.size(), updates, failed, rejected, more_false);
    for (const SuiteResult& r : results) {
      for (const std::string& line : r.window_above) std::printf("  %s\n", line.c_str());
    }
  }
  if (g_list_runs) {
    std::printf("runs with false alarms:\n");
    for (const SuiteResult& r : results) {
      for (const std::string& line : r.listed_runs) std::printf("  %s\n", line.c_str());
    }
  }
  if (smoother) {
    int fallbacks = 0;
    for (const SuiteResult& r : results) fallbacks += r.smoother_fallbacks;
    std::printf("batch fell back to the EKF on %d runs\n", fallbacks);
  }
  return 0;
}
