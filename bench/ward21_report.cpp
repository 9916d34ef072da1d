// The EKF on the ward21 suite (Ward & Iagnemma Sec. III): detection, delay and false-alarm
// figures with and without GNSS, and the paper's Table II (each tire coefficient at +-20 %).
// Simulates the suite in memory. Run: build/bench/ward21_report [--seed N] [--tire-dynamics]
// [--smoother] [--nominal] [--runs] [--seeds A-B [--single-law]] [--threshold T]
// [--low-speed-add A] [--low-speed V] [--ema P] [--min-wheel-speed V]
//   --tire-dynamics: the paper's propagation of v_bx through the tire law, for comparison;
//   --smoother: the batch smoother instead of the EKF, nominal rows only;
//   --nominal: without Table II; --runs: each run's line before each row;
//   --seeds: the front end on suites A to B, one line each, and how many meet every target;
//   --threshold ... --min-wheel-speed: the detector's parameters (ImmobilizationConfig).
// The nominal rows show the front end `filter` runs (a bank of filters over the soils
// vehicle.yaml lists, solvers/multiple_model_ekf.h) and the paper's single filter (without the
// front end's GNSS fading memory); Table II is the single filter's, as in the paper.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "evaluation/evaluation.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/batch_smoother.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {
namespace {

VelocityModel g_velocity_model = VelocityModel::kAccelerometerDriven;
bool g_smoother = false;
bool g_bank = true;   // the nominal rows' first pair; Table II uses the single filter
bool g_runs = false;  // --runs: one line per run of the nominal rows (misses, false alarms)
// --threshold, --low-speed-add, --low-speed, --ema, --min-wheel-speed: the detector's parameters
// (chosen empirically, as the paper says; try them on suites the figures are not reported on).
ImmobilizationConfig g_detector;

Evaluation RunSuite(const std::vector<DriveLog>& logs, bool gps,
                    const std::function<void(ModelConfig*)>& change) {
  std::vector<Evaluation> runs;
  for (const DriveLog& log : logs) {
    ModelConfig model = DefaultModelConfig(log.vehicle);
    model.immobilization = g_detector;
    change(&model);
    FilterRunOptions options;
    options.use_gps = gps;
    options.ekf.velocity_model = g_velocity_model;
    options.multiple_model = g_bank;
    options.ekf.gnss_fading_fixes = 0.0;  // the paper's filter (the bank does not fade)
    if (g_smoother) {
      BatchSmootherOptions smoother;
      smoother.filter = options;
      FilterResult rows;
      rows.estimates = SmoothBatch(log, model, smoother).estimates;
      runs.push_back(Evaluate(log, EstimateTable(rows.estimates)));
    } else {
      runs.push_back(Evaluate(log, EstimateTable(RunEkf(log, model, options).estimates)));
    }
    if (g_runs) {
      runs.back().name = "  run " + std::to_string(runs.size());
      PrintEvaluation(runs.back(), std::cout);
    }
  }
  return Combine(runs, "ward21");
}

void Print(const char* label, const Evaluation& ev) {
  std::printf("| %-22s | %2d/%-2zu | %6.3f | %5.3f %% (%ld) | %6.3f | %6.3f |\n", label,
              ev.detected(), ev.events.size(), ev.mean_detection_delay_s(),
              100.0 * ev.false_immobilized_fraction(), ev.false_immobilized_samples,
              ev.velocity_rmse, ev.disturbance_rmse);
}

std::vector<DriveLog> SimulateSuite(uint64_t seed) {
  std::vector<DriveLog> logs;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("ward21", seed)) {
    logs.push_back(sim::Simulate(run.scenario, run.seed).log);
  }
  return logs;
}

// The paper's targets for one suite: every hold-back detected, mean delay <= 0.4 s, false
// immobilized <= 0.2 % of samples with GNSS and <= 0.35 % without.
bool MeetsTargets(const Evaluation& ev, bool gps) {
  const double delay = ev.mean_detection_delay_s();
  return ev.detected() == static_cast<int>(ev.events.size()) && !(delay > 0.4) &&
         ev.false_immobilized_fraction() <= (gps ? 0.002 : 0.0035);
}

// --seeds A-B: the front end's nominal rows on many independent suites, one line each, and how
// many suites meet every target.
int ReportSeeds(uint64_t first, uint64_t last) {
  std::printf(
      "ward21, seeds %llu-%llu, the front end (%s), detector threshold %.2f + %.2f at "
      "low speed\n\n",
      static_cast<unsigned long long>(first), static_cast<unsigned long long>(last),
      g_bank ? "bank" : "single filter", g_detector.slip_threshold,
      g_detector.low_speed_threshold_add);
  std::printf("| seed | GNSS: det. | delay s | false | no GNSS: det. | delay s | false |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  struct Totals {
    int detected = 0, events = 0, suites_met = 0, over_false_bound = 0;
    long false_samples = 0, samples = 0;
  } totals[2];
  const auto nominal = [](ModelConfig*) {};
  for (uint64_t seed = first; seed <= last; ++seed) {
    const std::vector<DriveLog> logs = SimulateSuite(seed);
    std::printf("| %llu |", static_cast<unsigned long long>(seed));
    for (int g = 0; g < 2; ++g) {
      const bool gps = g == 0;
      const Evaluation ev = RunSuite(logs, gps, nominal);
      Totals& t = totals[g];
      t.detected += ev.detected();
      t.events += static_cast<int>(ev.events.size());
      t.false_samples += ev.false_immobilized_samples;
      t.samples += static_cast<long>(ev.samples);
      t.suites_met += MeetsTargets(ev, gps) ? 1 : 0;
      t.over_false_bound += ev.false_immobilized_fraction() > (gps ? 0.002 : 0.0035) ? 1 : 0;
      std::printf(" %d/%zu | %.3f | %.3f %% |", ev.detected(), ev.events.size(),
                  ev.mean_detection_delay_s(), 100.0 * ev.false_immobilized_fraction());
    }
    std::printf("\n");
  }
  const int suites = static_cast<int>(last - first + 1);
  for (int g = 0; g < 2; ++g) {
    const Totals& t = totals[g];
    std::printf(
        "\n%s: %d/%d hold-backs detected, every target met on %d of %d suites, false "
        "alarms above the bound on %d, %.3f %% of all samples",
        g == 0 ? "GNSS" : "no GNSS", t.detected, t.events, t.suites_met, suites, t.over_false_bound,
        100.0 * t.false_samples / std::max(1L, t.samples));
  }
  std::printf("\n");
  return 0;
}

}  // namespace
}  // namespace slipgraph

int main(int argc, char** argv) {
  using namespace slipgraph;  // NOLINT
  uint64_t seed = 1;
  uint64_t seeds_first = 0, seeds_last = 0;  // --seeds A-B
  bool nominal_only = false;
  for (int i = 1; i + 1 < argc; ++i) {
    const auto value = [&] { return std::strtod(argv[i + 1], nullptr); };
    if (std::strcmp(argv[i], "--seed") == 0) seed = std::strtoull(argv[i + 1], nullptr, 10);
    if (std::strcmp(argv[i], "--seeds") == 0) {
      char* end = nullptr;
      seeds_first = std::strtoull(argv[i + 1], &end, 10);
      seeds_last = *end == '-' ? std::strtoull(end + 1, nullptr, 10) : seeds_first;
    }
    if (std::strcmp(argv[i], "--threshold") == 0) g_detector.slip_threshold = value();
    if (std::strcmp(argv[i], "--low-speed-add") == 0) g_detector.low_speed_threshold_add = value();
    if (std::strcmp(argv[i], "--low-speed") == 0) g_detector.low_speed_mps = value();
    if (std::strcmp(argv[i], "--ema") == 0) g_detector.ema_samples = value();
    if (std::strcmp(argv[i], "--min-wheel-speed") == 0) g_detector.min_wheel_speed_mps = value();
  }
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--tire-dynamics") == 0) {
      g_velocity_model = VelocityModel::kTireDynamics;
    }
    if (std::strcmp(argv[i], "--smoother") == 0) g_smoother = true;
    if (std::strcmp(argv[i], "--nominal") == 0) nominal_only = true;
    if (std::strcmp(argv[i], "--runs") == 0) g_runs = true;
    if (std::strcmp(argv[i], "--single-law") == 0) g_bank = false;
  }
  if (seeds_first > 0) {
    if (g_smoother || seeds_last < seeds_first) {
      std::fprintf(stderr, "ward21_report: --seeds A-B (A <= B) runs the EKF front end only\n");
      return 2;
    }
    return ReportSeeds(seeds_first, seeds_last);
  }
  if (!g_bank) {  // one suite prints the bank's rows and the single filter's already
    std::fprintf(stderr, "ward21_report: --single-law goes with --seeds\n");
    return 2;
  }
  const std::vector<DriveLog> logs = SimulateSuite(seed);
  std::printf("ward21, seed %llu\n\n", static_cast<unsigned long long>(seed));
  std::printf("| %-22s | det.  | delay s | false immobilized | v RMSE | a_dist RMSE |\n", "case");
  std::printf("|---|---|---|---|---|---|\n");
  const auto nominal = [](ModelConfig*) {};
  Print(g_smoother ? "nominal, GNSS" : "bank, GNSS", RunSuite(logs, true, nominal));
  Print(g_smoother ? "nominal, no GNSS" : "bank, no GNSS", RunSuite(logs, false, nominal));
  if (g_smoother) return 0;  // the batch smoother: the two nominal rows only
  g_bank = false;
  Print("single filter, GNSS", RunSuite(logs, true, nominal));
  Print("single filter, no GNSS", RunSuite(logs, false, nominal));
  if (nominal_only) return 0;
  const struct {
    const char* name;
    std::function<double&(ModelConfig*)> field;
  } parameters[] = {
      {"C1", [](ModelConfig* m) -> double& { return m->tire.C1; }},
      {"At", [](ModelConfig* m) -> double& { return m->tire.At; }},
      {"R1", [](ModelConfig* m) -> double& { return m->rolling.R1; }},
      {"R2", [](ModelConfig* m) -> double& { return m->rolling.R2; }},
      {"A_roll", [](ModelConfig* m) -> double& { return m->rolling.A_roll; }},
  };
  for (const auto& p : parameters) {
    for (double factor : {1.2, 0.8}) {
      const std::string label =
          std::string(p.name) + (factor > 1.0 ? " +20 %" : " -20 %") + ", GNSS";
      Print(label.c_str(), RunSuite(logs, true, [&](ModelConfig* m) { p.field(m) *= factor; }));
    }
  }
  return 0;
}
