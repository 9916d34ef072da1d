#include "problems/identification_problem.h"

#include <algorithm>
#include <stdexcept>

#include "factors/diagonal_prior.h"

namespace slipgraph {

std::unique_ptr<IdentificationProblem> BuildIdentificationProblem(
    const std::vector<const DriveLog*>& logs, const ModelConfig& model,
    const std::vector<const std::vector<WardEstimate>*>& initial, const WardProblemOptions& options,
    const IdentificationPriors& priors) {
  if (logs.size() != initial.size() || logs.empty()) {
    throw std::invalid_argument("identification needs one front-end run per log");
  }
  auto out = std::make_unique<IdentificationProblem>();
  out->law = LawCoefficients(model.tire, model.rolling);
  out->radius_error = {0.0, 0.0};
  ceres::Problem::Options problem_options;
  problem_options.enable_fast_removal = false;
  out->problem = std::make_unique<ceres::Problem>(problem_options);
  ceres::Problem& problem = *out->problem;

  std::vector<AddedFactor> added;
  problem.AddParameterBlock(out->law.data(), kLawCoefficientCount);
  for (int i = 0; i < kLawCoefficientCount; ++i) {
    problem.SetParameterLowerBound(out->law.data(), i, priors.law_min[i]);
    problem.SetParameterUpperBound(out->law.data(), i, priors.law_max[i]);
  }
  for (int i = 0; i < kLawCoefficientCount; ++i) {
    out->law[i] = std::clamp(out->law[i], priors.law_min[i], priors.law_max[i]);
  }
  added.push_back(
      {"law_prior", problem.AddResidualBlock(
                        DiagonalPrior<kLawCoefficientCount>::Create(out->law, priors.law_sd),
                        nullptr, out->law.data())});
  problem.AddParameterBlock(out->radius_error.data(), 2);
  for (int i = 0; i < 2; ++i) {
    problem.SetParameterLowerBound(out->radius_error.data(), i, -priors.radius_error_bound);
    problem.SetParameterUpperBound(out->radius_error.data(), i, priors.radius_error_bound);
  }
  added.push_back(
      {"radius_prior",
       problem.AddResidualBlock(
           DiagonalPrior<2>::Create({0.0, 0.0}, {priors.radius_error_sd, priors.radius_error_sd}),
           nullptr, out->radius_error.data())});

  WardProblemOptions log_options = options;
  log_options.stiffness_prior_sd = 0.0;
  out->logs.resize(logs.size());
  for (size_t j = 0; j < logs.size(); ++j) {
    const WardFactorSource source(*logs[j], model, *initial[j], log_options);
    IdentificationLogBlocks& blocks = out->logs[j];
    const size_t n = source.size();
    blocks.times = source.times();
    blocks.states.resize(n);
    for (size_t k = 0; k < n; ++k) {
      std::copy((*initial[j])[k].x.begin(), (*initial[j])[k].x.end(), blocks.states[k].begin());
      problem.AddParameterBlock(blocks.states[k].data(), ward::kStateSize);
    }
    blocks.offsets = {initial[j]->back().accel_offset_mps2, initial[j]->back().gyro_offset_radps};
    problem.AddParameterBlock(blocks.offsets.data(), 2);
    source.AddStatePrior(0, blocks.states[0].data(), &problem, &added);
    source.AddOffsetPrior(blocks.offsets, blocks.offsets.data(), &problem, &added);
    GlobalBlocks globals;
    globals.offsets = blocks.offsets.data();
    globals.law = out->law.data();
    globals.radius_error = out->radius_error.data();
    for (size_t k = 0; k < n; ++k) {
      source.AddStep(k, k > 0 ? blocks.states[k - 1].data() : nullptr, blocks.states[k].data(),
                     globals, &problem, &added, &out->counts);
    }
  }
  for (const AddedFactor& a : added) out->blocks[a.kind].push_back(a.id);
  return out;
}

}  // namespace slipgraph
