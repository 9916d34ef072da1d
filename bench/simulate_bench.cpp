// Simulating 35 minutes of the LAGR robot at 100 Hz output (2 kHz internal integration): the
// physics, all sensors, truth and events, in memory. Run: build/bench/simulate_bench
#include <benchmark/benchmark.h>

#include "bench/long_drive.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace {

void BM_Simulate35MinAt100Hz(benchmark::State& state) {
  const sim::Scenario scenario = LongDrive(35.0);
  size_t rows = 0;
  for (auto _ : state) {
    const sim::SimResult result = sim::Simulate(scenario, 1);
    rows = result.log.imu.size();
    benchmark::DoNotOptimize(rows);
  }
  state.counters["imu_rows"] = static_cast<double>(rows);
  state.counters["simulated_s"] = scenario.duration_s();
}
BENCHMARK(BM_Simulate35MinAt100Hz)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace
}  // namespace slipgraph

BENCHMARK_MAIN();
