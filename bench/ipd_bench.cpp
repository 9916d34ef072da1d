// IPD speed on one core: evaluating one segment factor (a 2 s segment at 100 Hz, residual and
// the 3 x 13 Jacobian), the linearization of one identification-EKF update (prediction with
// its Jacobian and eq. 15's covariance terms), per segment, and the online calibrations (EKF and
// Ceres window) on a few minutes of ipd35, per update. Run: build/bench/ipd_bench
#include <benchmark/benchmark.h>

#include <memory>

#include "factors/ipd_segment_factor.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"
#include "solvers/ipd_calibration.h"
#include "solvers/ipd_graph_calibration.h"

namespace slipgraph {
namespace {

const DriveLog& Log() {
  static const DriveLog log = [] {
    sim::Scenario sc = sim::ExpandScenario("ipd35", 1).at(0).scenario;
    sc.commands.resize(60);  // a few minutes are enough
    return sim::Simulate(sc, 1).log;
  }();
  return log;
}

const std::vector<IpdSegment>& Segments() {
  static const std::vector<IpdSegment> segments = BuildIpdSegments(Log(), IpdOptions());
  return segments;
}

void BM_SegmentFactorEvaluate(benchmark::State& state) {
  const IpdSegment& seg = Segments().at(Segments().size() / 2);
  const std::unique_ptr<ceres::CostFunction> factor(IpdSegmentFactor::Create(
      seg.steps, seg.measured, Eigen::Matrix3d::Identity() * 1e-3, 9.80665));
  std::array<double, ipd::kAlphaSize> alpha{};
  alpha[0] = -0.05;
  const double* parameters[1] = {alpha.data()};
  double residual[3], jacobian[3 * ipd::kAlphaSize];
  double* jacobians[1] = {jacobian};
  for (auto _ : state) {
    factor->Evaluate(parameters, residual, jacobians);
    benchmark::DoNotOptimize(jacobian[0]);
  }
  state.counters["steps_per_segment"] = static_cast<double>(seg.steps.size());
}
BENCHMARK(BM_SegmentFactorEvaluate);

void BM_UpdateLinearization(benchmark::State& state) {
  // The bulk of one identification-EKF update: the segment's prediction with its 3 x 13
  // Jacobian and eq. (15)'s covariance terms (the 13-state Kalman algebra is small beside it).
  const std::vector<IpdSegment>& segments = Segments();
  size_t count = 0;
  for (auto _ : state) {
    std::array<double, ipd::kAlphaSize> alpha{};
    for (const IpdSegment& seg : segments) {
      const Eigen::Matrix<double, 3, ipd::kAlphaSize> H =
          LinearizeSegment(seg, alpha.data(), IpdOptions()).H;
      const ipd::PredictionCovarianceTerms terms = ipd::PredictionCovariance(
          seg.steps, alpha.data(), 9.80665, seg.sigma_start, seg.sigma_end);
      benchmark::DoNotOptimize(H(0, 0) + terms.measurement(0, 0));
      ++count;
    }
  }
  state.counters["segments_per_s"] =
      benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_UpdateLinearization)->Unit(benchmark::kMillisecond);

// A whole online calibration; the counter is its updates (EKF: one per segment; window: one
// solve per 0.5 s block, with the terrain memory's scoring) per second of computing.
template <typename Calibrate>
void RunCalibration(benchmark::State& state, Calibrate calibrate) {
  size_t updates = 0;
  for (auto _ : state) {
    const IpdCalibrationResult r = calibrate(Log());
    updates += r.update_t.size();
    benchmark::DoNotOptimize(r.final_alpha[0]);
  }
  state.counters["updates_per_s"] =
      benchmark::Counter(static_cast<double>(updates), benchmark::Counter::kIsRate);
  state.counters["log_s"] = Log().wheels.back().t - Log().wheels.front().t;
}
void BM_EkfCalibration(benchmark::State& state) {
  RunCalibration(state, [](const DriveLog& log) { return CalibrateIpdEkf(log); });
}
BENCHMARK(BM_EkfCalibration)->Unit(benchmark::kMillisecond);
void BM_WindowCalibration(benchmark::State& state) {
  RunCalibration(state, [](const DriveLog& log) { return CalibrateIpdWindow(log); });
}
BENCHMARK(BM_WindowCalibration)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slipgraph

BENCHMARK_MAIN();
