#include "problems/ward_batch_problem.h"

#include <ceres/normal_prior.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "problems/owned_functions.h"

namespace slipgraph {

WardProblem::~WardProblem() {
  if (problem == nullptr) return;
  OwnedFunctions functions;
  functions.TakeAll(*problem);
  problem.reset();
  functions.DeleteAll();
}

std::unique_ptr<WardProblem> BuildWardBatchProblem(const DriveLog& log, const ModelConfig& model,
                                                   const std::vector<WardEstimate>& initial,
                                                   const WardProblemOptions& options) {
  const WardFactorSource source(log, model, initial, options);
  auto out = std::make_unique<WardProblem>();
  const size_t n = source.size();
  out->times = source.times();
  out->states.resize(n);
  out->wheel_speeds.resize(n);
  for (size_t k = 0; k < n; ++k) {
    std::copy(initial[k].x.begin(), initial[k].x.end(), out->states[k].begin());
    out->wheel_speeds[k] = source.wheel_speeds(k);
  }
  out->offsets = {initial.back().accel_offset_mps2, initial.back().gyro_offset_radps};

  out->problem = std::make_unique<ceres::Problem>(OptionsOwningNoFunctions(false));
  ceres::Problem& problem = *out->problem;
  for (size_t k = 0; k < n; ++k) problem.AddParameterBlock(out->states[k].data(), ward::kStateSize);
  problem.AddParameterBlock(out->offsets.data(), 2);

  out->effect_terms = source.effect_terms();
  out->effects.assign(out->effect_terms.size(), 0.0);
  out->ignored_effects = source.effects_without_term();
  double* effects = nullptr;
  std::vector<AddedFactor> added;
  if (!out->effect_terms.empty()) {
    effects = out->effects.data();
    const int count = static_cast<int>(out->effect_terms.size());
    problem.AddParameterBlock(effects, count);
  }
  if (effects != nullptr && options.Builds("effect_prior")) {
    const int count = static_cast<int>(out->effect_terms.size());
    Eigen::VectorXd sd(count);
    for (int j = 0; j < count; ++j) sd[j] = out->effect_terms[j]->prior_sd;
    added.push_back(
        {"effect_prior", problem.AddResidualBlock(
                             new ceres::NormalPrior(Eigen::MatrixXd(sd.cwiseInverse().asDiagonal()),
                                                    Eigen::VectorXd::Zero(count)),
                             nullptr, effects)});
  }
  double* stiffness = nullptr;
  // Per factor added so far, the state it counts with (-1: a global prior, counted with the first).
  std::vector<long> node_state(added.size(), -1);
  if (options.stiffness_prior_sd > 0.0 && source.size() > 0 &&
      (effects == nullptr || options.stiffness_with_effects)) {
    out->stiffness.assign(source.stiffness_node_count(), 0.0);
    stiffness = out->stiffness.data();
    size_t k = 0;
    for (size_t j = 0; j < out->stiffness.size(); ++j) {
      source.AddStiffnessNode(j, stiffness, &problem, &added);
      // Each node's prior or walk step counts with the last state at or before the node.
      const double t = source.time(0) + static_cast<double>(j) * options.stiffness_node_s;
      while (k + 1 < n && source.time(k + 1) <= t) ++k;
      node_state.resize(added.size(), static_cast<long>(k));
    }
  }
  source.AddStatePrior(0, out->states[0].data(), &problem, &added);
  source.AddOffsetPrior(out->offsets, out->offsets.data(), &problem, &added);
  std::vector<long> state_of = std::move(node_state);
  state_of.resize(added.size(), -1);
  for (size_t k = 0; k < n; ++k) {
    source.AddStep(k, k > 0 ? out->states[k - 1].data() : nullptr, out->states[k].data(),
                   {out->offsets.data(), effects, stiffness}, &problem, &added, &out->counts);
    state_of.resize(added.size(), static_cast<long>(k));
  }
  for (size_t i = 0; i < added.size(); ++i) {
    out->blocks[added[i].kind].push_back(added[i].id);
    out->block_states[added[i].kind].push_back(state_of[i]);
  }
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
