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

// The front end over one simulated scenario, steps (wheel cycles) per second.
void BM_FrontEnd(benchmark::State& state, const char* scenario) {
  const sim::ScenarioRun run = sim::ExpandScenario(scenario, 1).at(0);
  const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  size_t cycles = 0;
  for (auto _ : state) {
    const FilterResult result = RunEkf(log, model);
    cycles += result.estimates.size();
    benchmark::DoNotOptimize(result.estimates.back());
  }
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
}
// One filter: fig5's vehicle.yaml states one law.
BENCHMARK_CAPTURE(BM_FrontEnd, EkfStep, "fig5")->Unit(benchmark::kMillisecond)->MinTime(2.0);
// A log whose vehicle.yaml lists the four soils its law was fitted over: the bank of five
// filters (solvers/multiple_model_ekf.h), the same step counted once.
BENCHMARK_CAPTURE(BM_FrontEnd, BankStep, "ward21/13")->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace slipgraph

BENCHMARK_MAIN();
