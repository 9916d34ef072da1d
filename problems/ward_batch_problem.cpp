#include "problems/ward_batch_problem.h"

#include <ceres/manifold.h>
#include <ceres/normal_prior.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "factors/diagonal_prior.h"

namespace slipgraph {

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

  ceres::Problem::Options problem_options;
  problem_options.enable_fast_removal = false;
  out->problem = std::make_unique<ceres::Problem>(problem_options);
  ceres::Problem& problem = *out->problem;
  for (size_t k = 0; k < n; ++k) problem.AddParameterBlock(out->states[k].data(), ward::kStateSize);
  problem.AddParameterBlock(out->offsets.data(), 2);

  out->force_terms = source.force_terms();
  out->force_term_values.assign(out->force_terms.size(), 0.0);
  for (const std::string& name : model.effects) {
    const int index = ModelEffectIndex(name);
    if (index < 0 && FindForceTerm(name) != nullptr) continue;
    if (index < 0) {
      out->ignored_effects.push_back(name);
    } else if (std::find(out->active_effects.begin(), out->active_effects.end(), index) ==
               out->active_effects.end()) {
      out->active_effects.push_back(index);
    }
  }
  std::sort(out->active_effects.begin(), out->active_effects.end());
  double* effects = nullptr;
  double* force_terms = nullptr;
  std::vector<AddedFactor> added;
  if (!out->force_terms.empty()) {
    // The accelerometer factor of force terms carries the catalogue's magnitudes too: held at 0
    // when the model has none of them.
    force_terms = out->force_term_values.data();
    const int count = static_cast<int>(out->force_terms.size());
    problem.AddParameterBlock(force_terms, count);
    Eigen::VectorXd sd(count);
    for (int j = 0; j < count; ++j) sd[j] = out->force_terms[j]->prior_sd;
    added.push_back(
        {"effect_prior", problem.AddResidualBlock(
                             new ceres::NormalPrior(Eigen::MatrixXd(sd.cwiseInverse().asDiagonal()),
                                                    Eigen::VectorXd::Zero(count)),
                             nullptr, force_terms)});
    if (out->active_effects.empty()) {
      problem.AddParameterBlock(out->effects.data(), kModelEffectCount);
      problem.SetParameterBlockConstant(out->effects.data());
      effects = out->effects.data();
    }
  }
  if (!out->active_effects.empty()) {
    effects = out->effects.data();
    problem.AddParameterBlock(effects, kModelEffectCount);
    std::vector<int> inactive;
    for (int i = 0; i < kModelEffectCount; ++i) {
      if (std::find(out->active_effects.begin(), out->active_effects.end(), i) ==
          out->active_effects.end()) {
        inactive.push_back(i);
      }
    }
    if (!inactive.empty()) {
      problem.SetManifold(effects, new ceres::SubsetManifold(kModelEffectCount, inactive));
    }
    // A weak prior: each magnitude's scale, several times what the catalogue calls typical.
    added.push_back(
        {"effect_prior",
         problem.AddResidualBlock(DiagonalPrior<kModelEffectCount>::Create({}, kModelEffectPriorSd),
                                  nullptr, effects)});
  }
  double* stiffness = nullptr;
  if (options.stiffness_prior_sd > 0.0 && effects == nullptr && source.size() > 0) {
    out->stiffness.assign(source.stiffness_node_count(), 0.0);
    stiffness = out->stiffness.data();
    for (size_t j = 0; j < out->stiffness.size(); ++j) {
      source.AddStiffnessNode(j, stiffness, &problem, &added);
    }
  }
  source.AddStatePrior(0, out->states[0].data(), &problem, &added);
  source.AddOffsetPrior(out->offsets, out->offsets.data(), &problem, &added);
  std::vector<long> state_of(added.size(), -1);
  for (size_t k = 0; k < n; ++k) {
    source.AddStep(k, k > 0 ? out->states[k - 1].data() : nullptr, out->states[k].data(),
                   {out->offsets.data(), effects, force_terms, stiffness}, &problem, &added,
                   &out->counts);
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
