#include "problems/owned_functions.h"

#include <algorithm>

namespace slipgraph {

ceres::Problem::Options OptionsOwningNoFunctions(bool enable_fast_removal) {
  ceres::Problem::Options options;
  options.enable_fast_removal = enable_fast_removal;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return options;
}

void OwnedFunctions::Take(const ceres::Problem& problem,
                          const std::vector<ceres::ResidualBlockId>& ids) {
  costs_.reserve(costs_.size() + ids.size());
  for (const ceres::ResidualBlockId id : ids) {
    costs_.push_back(problem.GetCostFunctionForResidualBlock(id));
    const ceres::LossFunction* loss = problem.GetLossFunctionForResidualBlock(id);
    if (loss != nullptr) losses_.push_back(loss);
  }
}

void OwnedFunctions::TakeAll(const ceres::Problem& problem) {
  std::vector<ceres::ResidualBlockId> ids;
  problem.GetResidualBlocks(&ids);
  Take(problem, ids);
}

void OwnedFunctions::DeleteAll() {
  const auto delete_each = [](auto* functions) {
    std::sort(functions->begin(), functions->end());
    functions->erase(std::unique(functions->begin(), functions->end()), functions->end());
    for (const auto* f : *functions) delete f;
    functions->clear();
  };
  delete_each(&costs_);
  delete_each(&losses_);
}

}  // namespace slipgraph
