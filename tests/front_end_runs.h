// The front end over named simulated runs of one seed (sim/scenarios.h names such as
// "ward21m/06"), each evaluated against its truth and pooled: for tests that compare two front-end
// settings on the same runs.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "evaluation/evaluation.h"
#include "solvers/ekf_runner.h"
#include "tests/sim_test_util.h"

namespace slipgraph {
namespace testing {

// adjust, when given, changes the model of each run (its vehicle's default) before the run.
inline Evaluation EvaluateFrontEnd(const std::vector<const char*>& names, uint64_t seed,
                                   const FilterRunOptions& options,
                                   const std::function<void(ModelConfig*)>& adjust = {}) {
  std::vector<Evaluation> runs;
  for (const char* name : names) {
    const DriveLog log = SimulatedScenario(name, seed);
    ModelConfig model = DefaultModelConfig(log.vehicle);
    if (adjust) adjust(&model);
    const FilterResult result = RunEkf(log, model, options);
    runs.push_back(Evaluate(log, EstimateTable(result.estimates)));
  }
  return Combine(runs, "runs");
}

}  // namespace testing
}  // namespace slipgraph
