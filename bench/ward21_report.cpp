// The EKF on the ward21 suite (Ward & Iagnemma Sec. III): detection, delay and false-alarm
// figures with and without GNSS, and the paper's Table II (each tire coefficient at +-20 %).
// Simulates the suite in memory. Run: build/bench/ward21_report [--seed N] [--tire-dynamics]
// [--smoother] [--nominal] [--runs] [--threshold T] [--low-speed-add A] [--low-speed V]
// [--ema P] (--tire-dynamics: the paper's propagation of v_bx through the tire
// law, for comparison; --smoother: the batch smoother instead of the EKF, nominal rows only;
// --nominal: without Table II; --runs: each run's line before each row). The nominal rows show the front end `filter` runs (a bank of
// filters over the soils vehicle.yaml lists, solvers/multiple_model_ekf.h) and the paper's single
// filter; Table II is the single filter's, as in the paper.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <functional>
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
bool g_bank = true;  // the nominal rows' first pair; Table II uses the single filter
bool g_runs = false;  // --runs: one line per run of the nominal rows (misses, false alarms)
// --threshold, --low-speed-add, --low-speed, --ema: the detector's parameters (chosen
// empirically, as the paper says; try them on suites the figures are not reported on).
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

}  // namespace
}  // namespace slipgraph

int main(int argc, char** argv) {
  using namespace slipgraph;  // NOLINT
  uint64_t seed = 1;
  bool nominal_only = false;
  for (int i = 1; i + 1 < argc; ++i) {
    const auto value = [&] { return std::strtod(argv[i + 1], nullptr); };
    if (std::strcmp(argv[i], "--seed") == 0) seed = std::strtoull(argv[i + 1], nullptr, 10);
    if (std::strcmp(argv[i], "--threshold") == 0) g_detector.slip_threshold = value();
    if (std::strcmp(argv[i], "--low-speed-add") == 0) g_detector.low_speed_threshold_add = value();
    if (std::strcmp(argv[i], "--low-speed") == 0) g_detector.low_speed_mps = value();
    if (std::strcmp(argv[i], "--ema") == 0) g_detector.ema_samples = value();
  }
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--tire-dynamics") == 0) {
      g_velocity_model = VelocityModel::kTireDynamics;
    }
    if (std::strcmp(argv[i], "--smoother") == 0) g_smoother = true;
    if (std::strcmp(argv[i], "--nominal") == 0) nominal_only = true;
    if (std::strcmp(argv[i], "--runs") == 0) g_runs = true;
  }
  std::vector<DriveLog> logs;
  for (const sim::ScenarioRun& run : sim::ExpandScenario("ward21", seed)) {
    logs.push_back(sim::Simulate(run.scenario, run.seed).log);
  }
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
