// The front end over named simulated runs of one seed (sim/scenarios.h names such as
// "ward21m/06"), each evaluated against its truth and pooled: for tests that compare two front-end
// settings on the same runs.
#pragma once

#include <cstdint>
#include <vector>

#include "evaluation/evaluation.h"
#include "solvers/ekf_runner.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace testing {

inline Evaluation EvaluateFrontEnd(const std::vector<const char*>& names, uint64_t seed,
                                   const FilterRunOptions& options) {
  std::vector<Evaluation> runs;
  for (const char* name : names) {
    const DriveLog log = SimulatedScenario(name, seed);
    const FilterResult result = RunEkf(log, DefaultModelConfig(log.vehicle), options);
    runs.push_back(Evaluate(log, EstimateTable(result.estimates)));
  }
  return Combine(runs, "runs");
}

}  // namespace testing
}  // namespace slipgraph
