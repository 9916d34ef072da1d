// EKF steps per second on one core: one step = one IMU update and one wheel cycle (prediction,
// updates, weak constraints, detector) plus an attitude sample, at 100 Hz, on the fig5 drive,
// through RunEkf (the stream merge included); and the bank of filters over a law's soils.
// Run: build/bench/ekf_bench
#include <benchmark/benchmark.h>

#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {
namespace {

// The front end over one simulated scenario, steps (wheel cycles) per second. slope_sd: the
// model's ModelConfig::tire_slip_stiffness_relative_sd (0: the law as exact, one filter run; the
// default adds two runs with the slope moved).
void BM_FrontEnd(benchmark::State& state, const char* scenario, double slope_sd) {
  const sim::ScenarioRun run = sim::ExpandScenario(scenario, 1).at(0);
  const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  ModelConfig model = DefaultModelConfig(log.vehicle);
  model.tire_slip_stiffness_relative_sd = slope_sd;
  size_t cycles = 0;
  for (auto _ : state) {
    const FilterResult result = RunEkf(log, model);
    cycles += result.estimates.size();
    benchmark::DoNotOptimize(result.estimates.back());
  }
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
}
// One filter: fig5's vehicle.yaml states one law, here taken as exact.
BENCHMARK_CAPTURE(BM_FrontEnd, EkfStep, "fig5", 0.0)->Unit(benchmark::kMillisecond)->MinTime(2.0);
// The same with the law's slope uncertain (the default): three filter runs.
BENCHMARK_CAPTURE(BM_FrontEnd, EkfStepWithSlopeSd, "fig5",
                  ModelConfig().tire_slip_stiffness_relative_sd)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
// A log whose vehicle.yaml lists the four soils its law was fitted over: the bank of five
// filters (solvers/multiple_model_ekf.h), the same step counted once.
BENCHMARK_CAPTURE(BM_FrontEnd, BankStep, "ward21/13", ModelConfig().tire_slip_stiffness_relative_sd)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace
}  // namespace slipgraph

BENCHMARK_MAIN();
