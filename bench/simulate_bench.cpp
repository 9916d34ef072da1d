// Simulating 35 minutes of the LAGR robot at 100 Hz output (2 kHz internal integration): the
// physics, all sensors, truth and events, in memory. Run: build/bench/simulate_bench
#include <benchmark/benchmark.h>

#include "sim/scenarios.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace {

sim::Scenario ThirtyFiveMinutes() {
  sim::Scenario sc;
  sc.name = "bench";
  sc.vehicle = sim::LagrVehicle();
  sc.course.patches = {{0.0, sim::FindTerrain("gravel")},
                       {300.0, sim::FindTerrain("grass")},
                       {700.0, sim::FindTerrain("mud")}};
  sc.course.hills = {{100.0, 40.0, 0.08, 0.02}, {500.0, 30.0, -0.06, 0.0}};
  sc.rest_start_s = 3.0;
  double total = sc.rest_start_s;
  for (int i = 0; total < 35.0 * 60.0; ++i) {
    const sim::CommandSegment segment{20.0, 0.3 + 0.1 * (i % 8), 0.2 * ((i % 5) - 2)};
    sc.commands.push_back(segment);
    total += segment.duration_s;
    if (i % 10 == 9) sc.holdbacks.push_back({total - 8.0, total - 4.0});
  }
  return sc;
}

void BM_Simulate35MinAt100Hz(benchmark::State& state) {
  const sim::Scenario scenario = ThirtyFiveMinutes();
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
