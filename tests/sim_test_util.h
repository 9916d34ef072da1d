// Small helpers for simulator tests: a named scenario's log, a flat single-terrain LAGR
// scenario, truth lookups and feeding a log to a filter.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "io/measurement_stream.h"
#include "sim/scenarios.h"
#include "sim/simulation.h"

namespace slipgraph {
namespace testing {

inline sim::Scenario FlatLagrScenario(const std::string& terrain, double speed_mps,
                                      double drive_s) {
  sim::Scenario sc;
  sc.name = "test";
  sc.vehicle = sim::LagrVehicle();
  sc.course.patches = {{0.0, sim::FindTerrain(terrain)}};
  sc.rest_start_s = 2.0;
  sc.commands = {{drive_s, speed_mps, 0.0}};
  return sc;
}

// The first run of a named scenario (sim/scenarios.h), simulated with the scenario's seed; its
// directory named after the scenario (for messages).
inline DriveLog SimulatedScenario(const std::string& scenario, uint64_t seed = 1) {
  const sim::ScenarioRun run = sim::ExpandScenario(scenario, seed).at(0);
  DriveLog log = sim::Simulate(run.scenario, run.seed).log;
  log.directory = scenario;
  return log;
}

// The log's samples (wheels, IMU, GNSS, attitude, truth) within [t0, t1] only; its events are
// the caller's.
inline void CutLog(DriveLog* log, double t0, double t1) {
  const auto cut = [t0, t1](auto* samples) {
    samples->erase(std::remove_if(samples->begin(), samples->end(),
                                  [t0, t1](const auto& s) { return s.t < t0 || s.t > t1; }),
                   samples->end());
  };
  cut(&log->wheels);
  cut(&log->imu);
  cut(&log->gps);
  cut(&log->attitude);
  cut(&log->truth);
}

// Mean of f(truth sample) over t in [t0, t1].
inline double MeanTruth(const DriveLog& log, double t0, double t1,
                        const std::function<double(const TruthSample&)>& f) {
  double sum = 0.0;
  int n = 0;
  for (const TruthSample& s : log.truth) {
    if (s.t >= t0 && s.t <= t1) sum += f(s), ++n;
  }
  return n > 0 ? sum / n : std::nan("");
}

// f of the truth sample nearest in time to each estimate (truth and estimates sorted by t).
template <typename Estimate>
std::vector<double> TruthAt(const DriveLog& log, const std::vector<Estimate>& estimates,
                            const std::function<double(const TruthSample&)>& f) {
  std::vector<double> out;
  out.reserve(estimates.size());
  size_t j = 0;
  for (const Estimate& e : estimates) {
    while (j + 1 < log.truth.size() &&
           std::abs(log.truth[j + 1].t - e.t) <= std::abs(log.truth[j].t - e.t)) {
      ++j;
    }
    out.push_back(log.truth.empty() ? std::nan("") : f(log.truth[j]));
  }
  return out;
}

// Feeds a log's merged streams to a filter with the WardEkf interface (WardEkf,
// MultipleModelEkf), in time order as RunEkf does. `take` (optional) may skip an entry by
// returning false; `after_wheels` (optional) sees each wheel cycle once the filter has it.
template <typename Filter>
void FeedStreams(const DriveLog& log, Filter* filter,
                 const std::function<bool(const StreamEntry&)>& take = {},
                 const std::function<void(const StreamEntry&)>& after_wheels = {}) {
  for (const StreamEntry& e : MergeStreams(log)) {
    if (take && !take(e)) continue;
    if (e.stream == Stream::kImu) filter->AddImu(log.imu[e.index]);
    if (e.stream == Stream::kAttitude) filter->AddAttitude(log.attitude[e.index]);
    if (e.stream == Stream::kGps) filter->AddGps(log.gps[e.index]);
    if (e.stream == Stream::kWheels) {
      const SideSpeeds s = DrivenSideSpeeds(log.wheels[e.index], log.vehicle.type);
      filter->AddWheels(log.wheels[e.index].t, s.left_radps, s.right_radps);
      if (after_wheels) after_wheels(e);
    }
  }
}

// Root of a monotonic increasing g on [lo, hi] by bisection.
inline double Bisect(const std::function<double(double)>& g, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace testing
}  // namespace slipgraph
