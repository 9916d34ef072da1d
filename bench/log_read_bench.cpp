// Reading a 35-minute, 100 Hz drive log (IMU, wheels, attitude and truth at 100 Hz, GNSS at
// 1 Hz): about 840,000 CSV rows. Run: build/bench/log_read_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>

#include "io/log_reader.h"
#include "io/log_writer.h"

namespace slipgraph {
namespace {

constexpr double kDurationS = 35.0 * 60.0;
constexpr double kRateHz = 100.0;

std::string WriteLongLog() {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "slipgraph_bench_35min_log").string();
  if (std::filesystem::exists(dir + "/truth.csv")) return dir;
  DriveLog log;
  Vehicle& v = log.vehicle;
  v.name = "bench";
  v.type = VehicleType::kDiffDriveCastor;
  v.mass_kg = 117.0, v.yaw_inertia_kgm2 = 15.0, v.wheel_radius_m = 0.25, v.track_width_m = 0.55;
  v.cg_to_front_m = 0.35, v.cg_to_rear_m = 0.55, v.cg_height_m = 0.3;
  const int n = static_cast<int>(kDurationS * kRateHz);
  for (int k = 0; k < n; ++k) {
    const double t = k / kRateHz;
    const double s = std::sin(0.1 * t);
    log.imu.push_back({t, 0.1 * s, 0.01, 9.81 + 0.02 * s, 0.001, -0.002, 0.05 * s});
    WheelSample w;
    w.t = t;
    w.omega_radps[0] = 3.9 + 0.1 * s;
    w.omega_radps[1] = 4.1 - 0.1 * s;
    log.wheels.push_back(w);
    log.attitude.push_back({t, 0.01 * s, -0.02 * s, 0.3 * t, kMissing, kMissing, kMissing});
    TruthSample truth;
    truth.t = t, truth.x = t, truth.vx = 1.0 + 0.01 * s, truth.a_dist = 0.0;
    truth.immobilized = 0.0;
    truth.slip.fill(0.03);
    log.truth.push_back(truth);
    if (k % 100 == 0) log.gps.push_back({t, t, 0.0, 0.0, 1.0, 0.0, 0.0, 0.5, 1.0, 0.1});
  }
  WriteDriveLog(log, dir);
  return dir;
}

void BM_ReadDriveLog35MinAt100Hz(benchmark::State& state) {
  const std::string dir = WriteLongLog();
  size_t rows = 0;
  for (auto _ : state) {
    const DriveLog log = ReadDriveLog(dir);
    rows = log.imu.size() + log.wheels.size() + log.attitude.size() + log.truth.size() +
           log.gps.size();
    benchmark::DoNotOptimize(rows);
  }
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["rows_per_s"] =
      benchmark::Counter(static_cast<double>(rows), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadDriveLog35MinAt100Hz)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace slipgraph

BENCHMARK_MAIN();
