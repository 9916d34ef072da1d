// EKF steps per second on one core: one step = one IMU update and one wheel cycle (prediction,
// updates, weak constraints, detector) at 100 Hz, on the bundled-style fig5 drive.
// Run: build/bench/ekf_bench
#include <benchmark/benchmark.h>

#include "io/measurement_stream.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ward_ekf.h"

namespace slipgraph {
namespace {

void BM_EkfStep(benchmark::State& state) {
  const sim::ScenarioRun run = sim::ExpandScenario("fig5", 1).at(0);
  const DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  const ModelConfig model = DefaultModelConfig(log.vehicle);
  const std::vector<StreamEntry> entries = MergeStreams(log);
  size_t cycles = 0;
  for (auto _ : state) {
    WardEkf ekf(log.vehicle, model);
    for (const StreamEntry& e : entries) {
      switch (e.stream) {
        case Stream::kImu:
          ekf.AddImu(log.imu[e.index]);
          break;
        case Stream::kWheels: {
          const SideSpeeds s = DrivenSideSpeeds(log.wheels[e.index], log.vehicle.type);
          ekf.AddWheels(log.wheels[e.index].t, s.left_radps, s.right_radps);
          ++cycles;
          break;
        }
        case Stream::kGps:
          ekf.AddGps(log.gps[e.index]);
          break;
        case Stream::kAttitude:
          ekf.AddAttitude(log.attitude[e.index]);
          break;
        default:
          break;
      }
    }
    benchmark::DoNotOptimize(ekf.Estimate());
  }
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EkfStep)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace slipgraph

BENCHMARK_MAIN();
