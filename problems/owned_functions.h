// Cost and loss functions kept by the problem's owner rather than by ceres::Problem. A problem
// that owns them (Problem::Options' default) keeps a map node per function, about 1 kB per state
// of a Ward problem, and frees them slowly; its owner instead collects those of the residual
// blocks it removes or leaves behind and deletes them.
#pragma once

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <vector>

namespace slipgraph {

// Problem::Options that leave the cost and loss functions to the caller.
ceres::Problem::Options OptionsOwningNoFunctions(bool enable_fast_removal);

class OwnedFunctions {
 public:
  // Takes the cost and loss functions of these residual blocks of `problem` (each once, should
  // one be shared by several blocks).
  void Take(const ceres::Problem& problem, const std::vector<ceres::ResidualBlockId>& ids);
  // Takes those of every residual block of `problem` (its owner's end).
  void TakeAll(const ceres::Problem& problem);
  // Deletes every function taken (after the blocks that use them left the problem).
  void DeleteAll();

 private:
  std::vector<const ceres::CostFunction*> costs_;
  std::vector<const ceres::LossFunction*> losses_;
};

}  // namespace slipgraph
