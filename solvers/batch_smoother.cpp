#include "solvers/batch_smoother.h"

#include <ceres/cost_function.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "factors/catalogue_terms.h"
#include "model/option_check.h"
#include "solvers/chain_covariance.h"
#include "solvers/chain_solver.h"
#include "solvers/model_choice_variance.h"
#include "solvers/smoothed_detection.h"

namespace slipgraph {

bool BatchSmootherOptions::IsValid(std::string* error) const {
  return OptionCheck("BatchSmootherOptions", error)
             .AtLeast("max_iterations", max_iterations, 1)
             .Positive("function_tolerance", function_tolerance)
             .NonNegative("step_sd_tolerance", step_sd_tolerance)
             .AtLeast("threads", threads, 1)
             .Positive("initial_trust_region_radius", initial_trust_region_radius)
             .NonNegative("min_immobilized_s", min_immobilized_s)
             .NonNegative("stiffness_gnss_margin", stiffness_gnss_margin) &&
         filter.IsValid(error) && problem.IsValid(error);
}

WardProblemOptions WithFilterSettings(WardProblemOptions options, const FilterRunOptions& filter) {
  options.use_gps = filter.use_gps;
  options.velocity_model = filter.ekf.velocity_model;
  options.wheel_still_radps = filter.ekf.wheel_still_radps;
  return options;
}

double PostProcessingStiffnessPriorSd(const ModelConfig& model, double requested) {
  if (!std::isnan(requested)) return requested;
  return model.ListsSoils() ? kPostProcessingStiffnessPriorSd : 0.0;
}

using namespace ward;  // NOLINT: state indices

namespace {

// The law's stated uncertainty as perturbed models whose shifts' outer products sum to it:
// with soil laws (ModelConfig::law_samples, n >= 2) each soil's deviation from the law over
// sqrt(n - 1) (their sample covariance, correlations included); else each coefficient with a
// stated sd, one sd off (ModelConfig::tire_sd, rolling_sd), and the slope at small slip (At and
// C2) scaled by exp(-sd) and exp(+sd), each weighted by 1/sqrt(2), as the front end takes it
// (ModelConfig::tire_slip_stiffness_relative_sd, SlipStiffnessSdScales), unless At's or C2's sd
// is stated.
struct LawPerturbation {
  std::string name;
  ModelConfig model;
  double weight = 1.0;  // of its residual shift
};
std::vector<LawPerturbation> LawPerturbations(const ModelConfig& model) {
  std::vector<LawPerturbation> out;
  const size_t n = model.law_samples.size();
  if (n >= 2) {
    const double scale = 1.0 / std::sqrt(static_cast<double>(n - 1));
    for (size_t i = 0; i < n; ++i) {
      const LawSample& soil = model.law_samples[i];
      ModelConfig m = model;
      m.tire.C1 += scale * (soil.tire.C1 - model.tire.C1);
      m.tire.At += scale * (soil.tire.At - model.tire.At);
      m.tire.C2 += scale * (soil.tire.C2 - model.tire.C2);
      m.rolling.R1 += scale * (soil.rolling.R1 - model.rolling.R1);
      m.rolling.A_roll += scale * (soil.rolling.A_roll - model.rolling.A_roll);
      m.rolling.R2 += scale * (soil.rolling.R2 - model.rolling.R2);
      out.push_back({"soil " + std::to_string(i + 1), m});
    }
    return out;
  }
  const auto add = [&](const char* name, double sd, auto apply) {
    if (!(sd > 0.0)) return;
    ModelConfig m = model;
    apply(m, sd);
    out.push_back({name, m});
  };
  add("C1", model.tire_sd.C1, [](ModelConfig& m, double sd) { m.tire.C1 += sd; });
  add("At", model.tire_sd.At, [](ModelConfig& m, double sd) { m.tire.At += sd; });
  add("C2", model.tire_sd.C2, [](ModelConfig& m, double sd) { m.tire.C2 += sd; });
  add("R1", model.rolling_sd.R1, [](ModelConfig& m, double sd) { m.rolling.R1 += sd; });
  add("A_roll", model.rolling_sd.A_roll, [](ModelConfig& m, double sd) { m.rolling.A_roll += sd; });
  add("R2", model.rolling_sd.R2, [](ModelConfig& m, double sd) { m.rolling.R2 += sd; });
  // The slope's sd where the coefficients' leave the slope (At, C2) unstated: not counted twice.
  if (model.tire_slip_stiffness_relative_sd > 0.0 && !(model.tire_sd.At > 0.0) &&
      !(model.tire_sd.C2 > 0.0)) {
    const auto scales = SlipStiffnessSdScales(model.tire_slip_stiffness_relative_sd);
    for (size_t i = 0; i < scales.size(); ++i) {
      ModelConfig m = model;
      ScaleSlipStiffness(scales[i], &m.tire);
      out.push_back({i == 0 ? "slip_stiffness -" : "slip_stiffness +", m, std::sqrt(0.5)});
    }
  }
  return out;
}

// The residual blocks of the factor kinds the law enters (TireLawFactorKinds), kind by kind.
std::vector<ceres::ResidualBlockId> LawBlocks(const WardProblem& problem) {
  std::vector<ceres::ResidualBlockId> ids;
  for (const std::string& kind : TireLawFactorKinds()) {
    const auto it = problem.blocks.find(kind);
    if (it != problem.blocks.end()) ids.insert(ids.end(), it->second.begin(), it->second.end());
  }
  return ids;
}

// A block's residuals as Problem::Evaluate gives them (loss-corrected); false when the block
// cannot be evaluated.
bool BlockResiduals(const ceres::Problem& problem, ceres::ResidualBlockId id,
                    std::vector<double>* r) {
  r->resize(problem.GetCostFunctionForResidualBlock(id)->num_residuals());
  return problem.EvaluateResidualBlock(id, true, nullptr, r->data(), nullptr);
}

// The consider covariance of the law's stated uncertainty (BatchSmootherOptions::
// consider_law_uncertainty): per state, the diagonal of sum_j dx_j dx_j'. Empty with a note when
// it cannot be computed.
std::vector<Eigen::Matrix<double, kStateSize, 1>> LawConsiderVariance(
    const DriveLog& log, const ModelConfig& model, const FilterResult& ekf,
    const WardProblemOptions& problem_options, WardProblem* problem,
    const std::vector<double*>& states, const std::vector<double*>& globals, int threads,
    std::vector<std::string>* notes) {
  std::vector<Eigen::Matrix<double, kStateSize, 1>> variance;
  const auto perturbations = LawPerturbations(model);
  if (perturbations.empty()) return variance;
  // The law moves only the residuals of its kinds: the shifts are taken on those blocks.
  ResidualShifts shifts;
  shifts.blocks = LawBlocks(*problem);
  std::vector<double> base, r;
  for (const ceres::ResidualBlockId id : shifts.blocks) {
    if (!BlockResiduals(*problem->problem, id, &r)) {
      notes->push_back("the law's uncertainty is not in the sd: a residual could not be evaluated");
      return {};
    }
    base.insert(base.end(), r.begin(), r.end());
  }
  WardProblemOptions law_options = problem_options;
  law_options.only_kinds = TireLawFactorKinds();  // the rest do not move with the law
  std::string names;
  for (const auto& [name, perturbed, weight] : perturbations) {
    std::unique_ptr<WardProblem> other =
        BuildWardBatchProblem(log, perturbed, ekf.estimates, law_options);
    if (other->states.size() != problem->states.size() ||
        other->stiffness.size() != problem->stiffness.size() ||
        other->effects.size() != problem->effects.size()) {
      notes->push_back("the law's uncertainty is not in the sd: the problem with " + name +
                       " has another structure");
      return {};
    }
    std::copy(problem->states.begin(), problem->states.end(), other->states.begin());
    other->offsets = problem->offsets;
    other->effects = problem->effects;
    std::copy(problem->stiffness.begin(), problem->stiffness.end(), other->stiffness.begin());
    // Its law's blocks, one for one with the problem's, fill the shift's rows exactly.
    const std::vector<ceres::ResidualBlockId> theirs = LawBlocks(*other);
    Eigen::VectorXd shift(static_cast<Eigen::Index>(base.size()));
    size_t row = 0;
    bool same = theirs.size() == shifts.blocks.size();
    for (size_t b = 0; same && b < theirs.size(); ++b) {
      same = BlockResiduals(*other->problem, theirs[b], &r) && row + r.size() <= base.size();
      for (size_t i = 0; same && i < r.size(); ++i, ++row) {
        shift[static_cast<Eigen::Index>(row)] = weight * (r[i] - base[row]);
      }
    }
    if (!same || row != base.size()) {
      notes->push_back("the law's uncertainty is not in the sd: the problem with " + name +
                       " has other residuals");
      return {};
    }
    shifts.columns.push_back(std::move(shift));
    names += (names.empty() ? "" : ", ") + name;
  }
  const ChainSensitivity sensitivity =
      ComputeChainSensitivity(problem->problem.get(), states, globals, shifts, threads);
  if (!sensitivity.ok) {
    notes->push_back("the law's uncertainty is not in the sd (" + sensitivity.error + ")");
    return {};
  }
  variance.assign(states.size(), Eigen::Matrix<double, kStateSize, 1>::Zero());
  for (const std::vector<Eigen::VectorXd>& dx : sensitivity.states) {
    for (size_t k = 0; k < dx.size(); ++k) variance[k] += dx[k].head<kStateSize>().cwiseAbs2();
  }
  notes->push_back("the sd include the tire law's stated uncertainty (" + names +
                   ": the estimate's shift with the law moved by each)");
  return variance;
}

SmootherResult SmoothBatchOnce(const DriveLog& log, const ModelConfig& model,
                               const FilterResult& ekf, const BatchSmootherOptions& options) {
  SmootherResult result;
  // The front end's run is copied into the result once the solve is done (a copy held through
  // the solve would add to its peak memory).
  result.estimates = ekf.estimates;
  if (ekf.estimates.size() < 2) {
    result.ekf = ekf;
    result.used_fallback = true;
    result.notes.push_back("fewer than two wheel samples: EKF estimates reported");
    return result;
  }
  WardProblemOptions problem_options = WithFilterSettings(options.problem, options.filter);
  if (options.bias_from_front_end && problem_options.accel_bias.empty()) {
    problem_options.accel_bias = ekf.stats.wheel_bias_checks;
  }
  std::unique_ptr<WardProblem> problem =
      BuildWardBatchProblem(log, model, ekf.estimates, problem_options);
  for (const std::string& effect : problem->ignored_effects) {
    result.notes.push_back("effect '" + effect +
                           "' is named in the model but has no model term yet: ignored");
  }

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = options.threads;
  solver_options.logging_type = ceres::SILENT;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.initial_trust_region_radius = options.initial_trust_region_radius;
  if (options.start != nullptr && options.start->size() == problem->states.size()) {
    for (size_t k = 0; k < problem->states.size(); ++k) {
      for (int i = 0; i < kStateSize; ++i) problem->states[k][i] = (*options.start)[k].x[i];
    }
    problem->offsets = {options.start->back().accel_offset_mps2,
                        options.start->back().gyro_offset_radps};
  }
  // Progress after each iteration, for a caller that shows it.
  class ProgressReporter : public ceres::IterationCallback {
   public:
    explicit ProgressReporter(const ProgressCallback& progress) : progress_(progress) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
      progress_({"batch smoother: iteration", summary.iteration, 0, summary.cost});
      return ceres::SOLVER_CONTINUE;
    }

   private:
    const ProgressCallback& progress_;
  };
  ProgressReporter reporter(options.progress);
  if (options.progress) solver_options.callbacks.push_back(&reporter);
  const std::map<std::string, double> initial_costs = CostByKind(*problem);
  const size_t n = problem->states.size();
  std::vector<double*> states;
  states.reserve(n);
  for (size_t k = 0; k < n; ++k) states.push_back(problem->states[k].data());
  std::vector<double*> globals = {problem->offsets.data()};
  if (!problem->effects.empty()) globals.push_back(problem->effects.data());
  for (double& node : problem->stiffness) globals.push_back(&node);
  bool solved = false;
  result.solver = "chain Levenberg-Marquardt";
  if (options.solver == BatchSolver::kChain) {
    ChainSolverOptions chain;
    chain.max_iterations = options.max_iterations;
    chain.function_tolerance = options.function_tolerance;
    chain.gradient_tolerance = solver_options.gradient_tolerance;
    chain.parameter_tolerance = solver_options.parameter_tolerance;
    chain.step_sd_tolerance = options.step_sd_tolerance;
    chain.initial_trust_region_radius = options.initial_trust_region_radius;
    chain.progress = options.progress;
    chain.progress_stage = "batch smoother: iteration";
    chain.threads = options.threads;
    solved = SolveOnChain(problem->problem.get(), states, globals, chain, &result.summary);
    if (!solved) result.notes.push_back(result.summary.message + ": solved by Ceres instead");
  }
  if (!solved) {
    ceres::Solve(solver_options, problem->problem.get(), &result.summary);
    result.solver = "Ceres trust region";
  }
  std::ostringstream breakdown;
  breakdown << "cost by factor (" << (options.start != nullptr ? "given start" : "EKF start")
            << " -> solution):";
  result.cost_by_kind = CostByKind(*problem);
  for (const auto& [kind, cost] : result.cost_by_kind) {
    breakdown << " " << kind << " " << initial_costs.at(kind) << " -> " << cost << ";";
  }
  result.notes.push_back(breakdown.str());
  if (!result.summary.IsSolutionUsable()) {
    result.used_fallback = true;
    result.notes.push_back("the solve failed (" + result.summary.message +
                           "): EKF estimates reported instead");
    result.ekf = ekf;
    return result;
  }
  if (result.summary.termination_type == ceres::NO_CONVERGENCE) {
    result.notes.push_back("the solve did not converge in " +
                           std::to_string(options.max_iterations) +
                           " iterations; its last iterate is reported");
  }
  result.final_cost = result.summary.final_cost;
  for (size_t j = 0; j < problem->effect_terms.size(); ++j) {
    result.effects.push_back({problem->effect_terms[j]->name, problem->effects[j], std::nan("")});
  }
  if (options.problem.stiffness_prior_sd > 0.0 && problem->stiffness.empty() &&
      !problem->effects.empty()) {
    result.notes.push_back(
        "the slip stiffness is the law's: with model effects it is estimated "
        "only when asked (WardProblemOptions::stiffness_with_effects)");
  }
  result.stiffness = problem->stiffness;
  if (std::any_of(result.stiffness.begin(), result.stiffness.end(),
                  [&](double theta) { return theta <= options.problem.stiffness_min + 1e-6; })) {
    char bound[32];
    std::snprintf(bound, sizeof(bound), "%.2f", options.problem.stiffness_min);
    result.notes.push_back(std::string("the slip stiffness reached its lower bound (theta = ") +
                           bound +
                           "): the terrain wants a far flatter tire law than the model's; the "
                           "law does not fit this log");
  }
  for (size_t k = 0; k < n; ++k) {
    WardEstimate& e = result.estimates[k];
    for (int i = 0; i < kStateSize; ++i) e.x[i] = problem->states[k][i];
    e.accel_offset_mps2 = problem->offsets[0];
    e.gyro_offset_radps = problem->offsets[1];
  }
  if (options.covariance) {
    std::vector<Eigen::Matrix<double, kStateSize, 1>> variance(n);  // the states' marginal ones
    {
      const ChainCovariance covariance =
          ComputeChainCovariance(problem->problem.get(), states, globals, options.threads);
      result.covariance_ok = covariance.ok;
      if (covariance.ok) {
        // The globals' order: the offsets (2), the effects, the stiffness nodes.
        const size_t first_node = 2 + problem->effects.size();
        for (size_t j = 0; j < problem->stiffness.size(); ++j) {
          const size_t g = first_node + j;
          result.stiffness_sd.push_back(std::sqrt(std::max(0.0, covariance.globals(g, g))));
        }
        for (size_t e = 0; e < result.effects.size(); ++e) {
          result.effects[e].sd = std::sqrt(std::max(0.0, covariance.globals(2 + e, 2 + e)));
        }
        for (size_t k = 0; k < n; ++k) variance[k] = covariance.states[k].diagonal();
        result.velocity_next_correlation.assign(n, 0.0);
        for (size_t k = 0; k + 1 < n; ++k) {
          const double var =
              covariance.states[k](kVbx, kVbx) * covariance.states[k + 1](kVbx, kVbx);
          result.velocity_next_correlation[k] =
              var > 0.0 ? covariance.next[k](kVbx, kVbx) / std::sqrt(var) : 0.0;
        }
      } else {
        result.notes.push_back("covariance recovery failed (" + covariance.error +
                               "): EKF sd reported");
      }
    }  // the covariance's blocks freed before the law's consider builds its own problems
    if (result.covariance_ok) {
      std::vector<Eigen::Matrix<double, kStateSize, 1>> law;
      if (options.consider_law_uncertainty) {
        law = LawConsiderVariance(log, model, ekf, problem_options, problem.get(), states, globals,
                                  options.threads, &result.notes);
      }
      for (size_t k = 0; k < n; ++k) {
        for (int i = 0; i < kStateSize; ++i) {
          const double consider = law.empty() ? 0.0 : law[k](i);
          result.estimates[k].sd[i] = std::sqrt(std::max(0.0, variance[k](i)) + consider);
        }
      }
    }
  }
  DetectImmobilizationOnSmoothedStates(model, log.vehicle, options.min_immobilized_s,
                                       &result.estimates);
  result.notes.insert(result.notes.begin(), problem->counts.Describe());
  problem.reset();
  result.ekf = ekf;
  return result;
}

// SmoothBatchOnce, and with BatchSmootherOptions::regate_decay_prior a second solve gated by the
// first's slip.
SmootherResult SmoothBatchRegated(const DriveLog& log, const ModelConfig& model,
                                  const FilterResult& ekf, const BatchSmootherOptions& options) {
  if (!options.regate_decay_prior || !options.problem.decay_gate_slip.empty()) {
    return SmoothBatchOnce(log, model, ekf, options);
  }
  BatchSmootherOptions first_options = options;
  first_options.covariance = false;
  SmootherResult first = SmoothBatchOnce(log, model, ekf, first_options);
  if (first.used_fallback) return first;  // the EKF's estimates, sd included (no covariance ran)
  first.ekf = FilterResult{};  // the caller's `ekf` (not held twice through the second solve)
  // The smoothed slip (DetectImmobilizationOnSmoothedStates leaves the mean of the two sides in
  // slip_ema) gates the second solve, which starts from the first.
  BatchSmootherOptions second_options = options;
  std::vector<double>& gate = second_options.problem.decay_gate_slip;
  const double threshold = model.weak_constraints.slip_threshold;
  long changed = 0;
  for (size_t k = 0; k < first.estimates.size(); ++k) {
    gate.push_back(first.estimates[k].slip.slip_ema);
    changed += (gate.back() >= threshold) != (ekf.estimates[k].slip.slip_ema >= threshold);
  }
  second_options.start = &first.estimates;
  SmootherResult second = SmoothBatchOnce(log, model, ekf, second_options);
  if (second.used_fallback) {
    SmootherResult result = SmoothBatchOnce(log, model, ekf, options);
    result.notes.push_back(
        "weak constraint 2 re-gated by the smoother's own slip: that solve failed, the EKF-gated "
        "solution is reported");
    return result;
  }
  second.notes.push_back("weak constraint 2 gated by a first solve's slip, not the EKF's EMA (" +
                         std::to_string(changed) + " of " + std::to_string(gate.size()) +
                         " states changed side of thresh_i)");
  return second;
}

// BatchSmootherOptions::model_choice_variance: `kept`'s sd widened by `other`'s solution, whose
// log-likelihood ratio against it is `log_ratio`. Both need their covariance. The correlation of
// successive velocity errors (velocity_next_correlation) stays the kept solution's own.
void AddOtherModelsVariance(const SmootherResult& other, double log_ratio,
                            const BatchSmootherOptions& options, const std::string& name,
                            SmootherResult* kept) {
  if (!options.model_choice_variance || !options.covariance) return;
  if (!kept->covariance_ok || !other.covariance_ok) {
    kept->notes.push_back("the sd do not count the solution with " + name +
                          ": no covariance for both");
    return;
  }
  const double p = OtherModelProbability(log_ratio);
  AddModelChoiceVariance(other.estimates, p, &kept->estimates);
  char text[160];
  std::snprintf(
      text, sizeof(text),
      "the sd count the solution with %s, its probability %.2f by GNSS's likelihood ratio",
      name.c_str(), p);
  kept->notes.push_back(text);
}

// The GNSS factors' cost at a solution (NaN without GNSS factors).
double GnssCost(const SmootherResult& result) {
  const auto it = result.cost_by_kind.find("gnss");
  return it == result.cost_by_kind.end() ? std::nan("") : it->second;
}

}  // namespace

SmootherResult SmoothBatch(const DriveLog& log, const ModelConfig& model,
                           const BatchSmootherOptions& options) {
  return SmoothBatch(log, model, RunEkf(log, model, options.filter), options);
}

SmootherResult SmoothBatch(const DriveLog& log, const ModelConfig& model, const FilterResult& ekf,
                           const BatchSmootherOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  SmootherResult result = SmoothBatchRegated(log, model, ekf, options);
  if (result.used_fallback || result.stiffness.empty() ||
      !std::isfinite(options.stiffness_gnss_margin)) {
    return result;
  }
  const double with_stiffness = GnssCost(result);
  if (!std::isfinite(with_stiffness)) {
    result.notes.push_back("the slip stiffness is not checked against GNSS: no GNSS factors");
    return result;
  }
  BatchSmootherOptions as_given_options = options;
  as_given_options.problem.stiffness_prior_sd = 0.0;
  SmootherResult as_given = SmoothBatchRegated(log, model, ekf, as_given_options);
  if (as_given.used_fallback) {
    result.notes.push_back(
        "the slip stiffness is not checked against GNSS: the solve with the law as given failed");
    return result;
  }
  const double without = GnssCost(as_given);
  char costs[96];
  std::snprintf(costs, sizeof(costs), "GNSS cost %.2f with it, %.2f with the law as given",
                with_stiffness, without);
  if (!(with_stiffness - without > options.stiffness_gnss_margin)) {
    result.notes.push_back(std::string("the estimated slip stiffness kept: ") + costs);
    // log L(as given) - log L(stiffness) = the stiffness's GNSS cost - the law's.
    AddOtherModelsVariance(as_given, with_stiffness - without, options, "the law as given",
                           &result);
    return result;
  }
  const auto [lo, hi] = std::minmax_element(result.stiffness.begin(), result.stiffness.end());
  char range[64];
  std::snprintf(range, sizeof(range), "theta %.2f to %.2f", *lo, *hi);
  as_given.notes.push_back(
      std::string("the slip stiffness was estimated (") + range +
      ") and not kept: its velocities fit GNSS worse than the law's as given (" + costs +
      "); the law's slope is not what the model lacks here, the law as given is reported");
  AddOtherModelsVariance(result, without - with_stiffness, options, "the estimated stiffness",
                         &as_given);
  return as_given;
}

std::vector<WardEstimate> DisturbanceWithEffects(const SmootherResult& result, const DriveLog& log,
                                                 const ModelConfig& model,
                                                 const EffectTerms* terms) {
  std::vector<WardEstimate> estimates = result.estimates;
  const EffectTerms& known = TermsOrCatalogue(terms);
  const ward::Params params = ward::MakeParams(log.vehicle, model);
  for (const EffectEstimate& effect : result.effects) {
    const EffectTerm* term = known.Find(effect.name);
    // A model parameter's force (the rolling law's, rescaled) is the model's own, not external.
    if (term == nullptr || term->kind != EffectKind::kForce || term->model_parameter) continue;
    for (WardEstimate& e : estimates) {
      e.x[ward::kAdist] +=
          effect.value *
          (*term->force)(e.x.data(), EffectContextAt(log, model, params, *term, e.t), params);
    }
  }
  return estimates;
}

std::string DescribeSmootherRun(const SmootherResult& result) {
  std::ostringstream out;
  const ceres::Solver::Summary& s = result.summary;
  if (result.solver.empty()) {
    out << "smoother: no solve\n";
  } else {
    out << "smoother: " << result.solver << ", " << s.iterations.size() << " iterations, cost "
        << s.initial_cost << " -> " << s.final_cost << ", "
        << ceres::TerminationTypeToString(s.termination_type) << " (" << s.message << ")\n";
  }
  out << "  " << (result.used_fallback ? "FALLBACK to the EKF" : "smoothed estimates")
      << ", covariance " << (result.covariance_ok ? "recovered" : "not recovered") << "\n";
  for (const EffectEstimate& e : result.effects) {
    out << "  effect " << e.name << ": " << e.value << " +- " << e.sd << "\n";
  }
  if (!result.stiffness.empty()) {
    const auto [lo, hi] = std::minmax_element(result.stiffness.begin(), result.stiffness.end());
    out << "  tire law's slip stiffness x (1 + theta): theta from " << *lo << " to " << *hi
        << " over " << result.stiffness.size() << " nodes";
    if (!result.stiffness_sd.empty()) out << " (sd of the first " << result.stiffness_sd[0] << ")";
    out << "\n";
  }
  for (const std::string& note : result.notes) out << "  " << note << "\n";
  return out.str();
}

}  // namespace slipgraph
