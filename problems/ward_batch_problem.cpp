#include "problems/ward_batch_problem.h"

#include <algorithm>

namespace slipgraph {

std::unique_ptr<WardProblem> BuildWardBatchProblem(const DriveLog& log, const ModelConfig& model,
                                                   const FilterResult& ekf,
                                                   const WardProblemOptions& options) {
  const WardFactorSource source(log, model, ekf, options);
  auto out = std::make_unique<WardProblem>();
  const size_t n = source.size();
  out->times = source.times();
  out->states.resize(n);
  out->wheel_speeds.resize(n);
  for (size_t k = 0; k < n; ++k) {
    std::copy(ekf.estimates[k].x.begin(), ekf.estimates[k].x.end(), out->states[k].begin());
    out->wheel_speeds[k] = source.wheel_speeds(k);
  }
  out->offsets = {ekf.estimates.back().accel_offset_mps2, ekf.estimates.back().gyro_offset_radps};

  ceres::Problem::Options problem_options;
  problem_options.enable_fast_removal = false;
  out->problem = std::make_unique<ceres::Problem>(problem_options);
  ceres::Problem& problem = *out->problem;
  for (size_t k = 0; k < n; ++k) problem.AddParameterBlock(out->states[k].data(), ward::kStateSize);
  problem.AddParameterBlock(out->offsets.data(), 2);

  std::vector<AddedFactor> added;
  source.AddStatePrior(0, out->states[0].data(), &problem, &added);
  source.AddOffsetPrior(out->offsets, out->offsets.data(), &problem, &added);
  for (size_t k = 0; k < n; ++k) {
    source.AddStep(k, k > 0 ? out->states[k - 1].data() : nullptr, out->states[k].data(),
                   out->offsets.data(), &problem, &added, &out->counts);
  }
  for (const AddedFactor& factor : added) out->blocks[factor.kind].push_back(factor.id);
  return out;
}

std::map<std::string, double> CostByKind(const WardProblem& problem) {
  std::map<std::string, double> costs;
  for (const auto& [kind, ids] : problem.blocks) {
    double total = 0.0;
    for (ceres::ResidualBlockId id : ids) {
      double cost = 0.0;
      problem.problem->EvaluateResidualBlock(id, true, &cost, nullptr, nullptr);
      total += cost;
    }
    costs[kind] = total;
  }
  return costs;
}

}  // namespace slipgraph
