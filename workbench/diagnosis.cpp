#include "workbench/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

#include "factors/ward_state.h"
#include "model/option_check.h"
#include "solvers/run_concurrently.h"
#include "workbench/effect_signatures.h"
#include "workbench/noise_scale.h"

namespace slipgraph {
namespace {

StreamReport ReportStream(const std::string& name, const std::vector<double>& r,
                          const DiagnosisOptions& options) {
  StreamReport s;
  s.name = name;
  double sum = 0.0;
  for (double v : r) {
    if (std::isfinite(v)) sum += v * v, ++s.samples;
  }
  if (s.samples == 0) return s;
  s.rms = std::sqrt(sum / s.samples);
  s.chi_square_p = ChiSquareUpperTail(sum, static_cast<double>(s.samples));
  s.consistent = s.chi_square_p >= options.alpha;
  s.whiteness = LjungBox(r, std::min<int>(options.whiteness_lags, s.samples / 4));
  s.white = s.whiteness.p_value >= options.alpha;
  return s;
}

// The force balance as a stream: u normalized by its full sd (noise and the solution's own).
std::vector<double> ForceBalance(const ModelResiduals& m, std::vector<double>* t) {
  std::vector<double> r;
  for (const StateContext& c : m.states) {
    if (!std::isfinite(c.unexplained_force)) continue;
    t->push_back(c.t);
    r.push_back(c.unexplained_force /
                std::sqrt(c.force_sd * c.force_sd + c.force_state_sd * c.force_state_sd));
  }
  return r;
}

// The operating conditions over a failure segment: mean speed, |pitch|, |yaw rate|.
void SetConditions(const ModelResiduals& m, FailureSegment* f) {
  double speed = 0.0, pitch = 0.0, yaw = 0.0;
  int n = 0;
  for (const StateContext& c : m.states) {
    if (c.t < f->t_start || c.t > f->t_end) continue;
    speed += std::abs(c.x[ward::kVbx]), pitch += std::abs(c.pitch_rad);
    yaw += std::abs(c.x[ward::kYawRate]), ++n;
  }
  if (n > 0)
    f->speed_mps = speed / n, f->abs_pitch_rad = pitch / n, f->abs_yaw_rate_radps = yaw / n;
}

struct Series {
  std::string name;
  std::vector<double> t, r;
};

std::vector<FailureSegment> FindFailures(const std::vector<Series>& streams,
                                         const ModelResiduals& m, const DiagnosisOptions& options) {
  if (m.states.empty()) return {};
  const double t0 = m.states.front().t, t1 = m.states.back().t;
  const size_t windows = std::max<size_t>(1, std::ceil((t1 - t0) / options.window_s));
  const double level = options.alpha / (windows * std::max<size_t>(1, streams.size()));
  std::vector<std::set<std::string>> flagged(windows);
  for (const Series& s : streams) {
    std::vector<double> sum(windows, 0.0);
    std::vector<int> count(windows, 0);
    for (size_t i = 0; i < s.t.size(); ++i) {
      if (!std::isfinite(s.r[i])) continue;
      const size_t w = std::min(windows - 1, static_cast<size_t>((s.t[i] - t0) / options.window_s));
      sum[w] += s.r[i] * s.r[i], ++count[w];
    }
    for (size_t w = 0; w < windows; ++w) {
      if (count[w] > 0 && ChiSquareUpperTail(sum[w], count[w]) < level) flagged[w].insert(s.name);
    }
  }
  std::vector<FailureSegment> out;
  for (size_t w = 0; w < windows; ++w) {
    if (flagged[w].empty()) continue;
    const double a = t0 + w * options.window_s, b = std::min(t1, a + options.window_s);
    if (!out.empty() && out.back().t_end >= a - 1e-9) {
      out.back().t_end = b;
      for (const std::string& name : flagged[w]) {
        if (std::find(out.back().streams.begin(), out.back().streams.end(), name) ==
            out.back().streams.end())
          out.back().streams.push_back(name);
      }
    } else {
      out.push_back({a, b, {flagged[w].begin(), flagged[w].end()}});
    }
  }
  for (FailureSegment& f : out) SetConditions(m, &f);
  return out;
}

CandidateScore Score(const EffectSignature& signature, const EffectRegistry& registry,
                     const ModelResiduals& m, const DriveLog& log, const ModelConfig& model) {
  CandidateScore c;
  c.effect = signature.effect;
  c.test = signature.test;
  c.added_as = registry.FindTerm(signature.effect) != nullptr ? "smoother term"
               : signature.correct                            ? "measurement correction"
                                                              : "";
  double searched = 1.0, precision = 0.0, weighted = 0.0, model_precision = 0.0;
  for (const SignatureSeries& s : signature.series(m, log, model)) {
    const SlopeFit fit =
        s.fit ? *s.fit : FitSlopeHac(s.y, s.g, s.y_common_sd, s.y_common_next_corr);
    if (fit.n == 0 || !(fit.sd > 0.0)) continue;
    c.series.push_back({s.stream, fit});
    if (s.graph_column) c.graph_column = s.graph_column;
    ++c.dof;
    searched = std::max(searched, s.searched);
    if (!s.where.empty()) c.where = s.where;
    if (!s.windows.empty()) c.windows = s.windows;
    precision += 1.0 / (fit.sd * fit.sd);
    weighted += fit.slope / (fit.sd * fit.sd);
    const double naive = fit.naive_sd > 0.0 ? fit.naive_sd : fit.sd;
    model_precision += 1.0 / (naive * naive);
  }
  if (c.dof == 0) return c;
  // One magnitude seen through every series: their precision-weighted mean, tested against
  // |theta| <= negligible (a Wald test on the score-test slope; chi-square with 1 dof).
  c.magnitude = weighted / precision;
  c.magnitude_sd = 1.0 / std::sqrt(precision);
  const double negligible = signature.negligible ? signature.negligible(log) : 0.0;
  c.negligible = negligible;
  const double z = std::max(0.0, std::abs(c.magnitude) - negligible) / c.magnitude_sd;
  c.statistic = z * z;
  c.dof = 1;
  c.searched = searched;
  c.dispersion = std::max(1.0, model_precision / precision);
  c.p_value = std::min(1.0, NormalTwoSided(z) * searched);
  return c;
}

// One fit: the smoother with `effect` switched on (on `windows` when it acts on windows), from
// the solution without it; ok is false when the solve failed.
struct Fit {
  bool ok = false;
  double likelihood_ratio = 0.0, value = 0.0, sd = 0.0;
};
Fit FitEffect(const DriveLog& log, const ModelConfig& model, const SmootherResult& without,
              const DiagnosisOptions& options, const std::string& effect,
              const std::vector<std::pair<double, double>>& windows) {
  ModelConfig with = model;
  with.effects.push_back(effect);
  for (const auto& [t0, t1] : windows) with.effect_windows.push_back({effect, t0, t1});
  BatchSmootherOptions smoother = options.smoother;
  if (!without.used_fallback) smoother.start = &without.estimates;  // a few iterations from there
  // The cost to 1e-7 of itself (about 0.001 on these logs) is enough for a likelihood ratio.
  smoother.function_tolerance = 1e-7;
  smoother.initial_trust_region_radius = options.fit_initial_trust_region_radius;
  // A fit reports its cost and its term's magnitude and sd: the states' sd and what the law's
  // uncertainty adds to them are not read.
  smoother.consider_law_uncertainty = false;
  smoother.model_choice_variance = false;
  const SmootherResult fit = SmoothBatch(log, with, without.ekf, smoother);
  Fit out;
  if (fit.used_fallback) return out;
  for (const EffectEstimate& e : fit.effects) {
    if (e.name != effect) continue;
    out.ok = true;
    out.likelihood_ratio = std::max(0.0, 2.0 * (without.final_cost - fit.final_cost));
    out.value = e.value;
    out.sd = e.sd;
  }
  return out;
}

// The candidates with a smoother term (the best `options.fit_candidates` of them), each fitted:
// its statistic becomes the quasi-likelihood ratio and its p-value that statistic's
// (CandidateScore). candidate_count: the Bonferroni multiplier the score tests had.
void FitAndCompare(const DriveLog& log, const ModelConfig& model, const SmootherResult& without,
                   const DiagnosisOptions& options, const EffectRegistry& registry,
                   size_t candidate_count, std::vector<CandidateScore>* candidates) {
  const size_t to_fit =
      options.fit_candidates < 0 ? candidates->size() : static_cast<size_t>(options.fit_candidates);
  std::vector<CandidateScore*> chosen;
  for (CandidateScore& c : *candidates) {
    if (chosen.size() >= to_fit) break;
    const EffectTerm* term = registry.FindTerm(c.effect);
    if (term == nullptr || c.dof == 0) continue;
    if (term->acts_on_windows && c.windows.empty()) continue;
    chosen.push_back(&c);
  }
  // The fits are independent solves from the same solution, applied in the candidates' order.
  std::vector<Fit> fits(chosen.size());
  RunConcurrently(chosen.size(), options.threads, [&](size_t i) {
    fits[i] = FitEffect(log, model, without, options, chosen[i]->effect, chosen[i]->windows);
  });
  for (size_t i = 0; i < chosen.size(); ++i) {
    const Fit& fit = fits[i];
    if (!fit.ok) continue;
    CandidateScore& c = *chosen[i];
    c.fitted = true;
    c.likelihood_ratio = fit.likelihood_ratio;
    c.score_statistic = c.statistic;
    c.score_p_value = c.p_value;
    c.score_magnitude = c.magnitude;
    c.score_magnitude_sd = c.magnitude_sd;
    c.magnitude = fit.value;
    c.magnitude_sd = fit.sd;
    c.statistic = c.likelihood_ratio / c.dispersion;
    c.p_value =
        std::min(1.0, NormalTwoSided(std::sqrt(c.statistic)) * c.searched * candidate_count);
    c.significant = c.p_value < options.alpha;
  }
}

// CandidateScore::detectable. A score test rejects |theta| <= negligible when
// (|theta| - negligible) / sd passes the two-sided critical z of alpha over its search and the
// candidates scored; a fitted one when |theta| / (sd sqrt(dispersion)) does (its statistic, the
// likelihood ratio over the dispersion, is about that squared). 80 % power adds z = 0.84.
void SetDetectable(double alpha, size_t candidate_count, CandidateScore* c) {
  if (c->dof == 0 || !(c->magnitude_sd > 0.0)) return;
  const double tests = c->searched * static_cast<double>(candidate_count);
  const double critical = NormalTwoSidedQuantile(std::min(1.0, alpha / tests));
  constexpr double kPower80 = 0.8416212335729143;  // the standard normal's 80 % quantile
  c->detectable = (c->fitted ? 0.0 : c->negligible) + (critical + kPower80) * c->test_sd();
}

// CandidateScore::implausible: empty unless the fit's +-2 sd interval misses the range (a
// fitted magnitude's sd widened by the dispersion, as its test is).
std::string ImplausibleBy(const PlausibleRange& range, const CandidateScore& c) {
  const double sd = c.test_sd();
  if (c.magnitude + 2.0 * sd >= range.low && c.magnitude - 2.0 * sd <= range.high) return "";
  std::ostringstream out;
  out << std::setprecision(3) << "outside the plausible " << range.low << " to " << range.high
      << " (" << range.basis << ")";
  return out.str();
}

}  // namespace

const CandidateScore* BestExplanation(const std::vector<CandidateScore>& candidates) {
  for (const CandidateScore& c : candidates) {
    if (c.significant && c.implausible.empty()) return &c;
  }
  return nullptr;
}

bool DiagnosisOptions::IsValid(std::string* error) const {
  return OptionCheck("DiagnosisOptions", error)
             .Require("alpha", alpha > 0.0 && alpha < 1.0, alpha, "must lie in (0, 1)")
             .Positive("window_s", window_s)
             .AtLeast("whiteness_lags", whiteness_lags, 1)
             .AtLeast("threads", threads, 1)
             .Positive("fit_initial_trust_region_radius", fit_initial_trust_region_radius)
             .NonNegative("varying_law_prior_sd", varying_law_prior_sd)
             .Positive("varying_law_node_s", varying_law_node_s)
             .Positive("varying_law_walk_sd", varying_law_walk_sd) &&
         smoother.IsValid(error);
}

Diagnosis Diagnose(const DriveLog& log, const ModelConfig& model, const DiagnosisOptions& given) {
  std::string error;
  if (!given.IsValid(&error)) throw std::invalid_argument(error);
  const EffectRegistry& registry =
      given.effects != nullptr ? *given.effects : EffectRegistry::Catalogue();
  DiagnosisOptions options = given;
  options.smoother.problem.effect_terms = &registry.terms();
  if (options.varying_law_prior_sd > 0.0) {
    WardProblemOptions& problem = options.smoother.problem;
    problem.stiffness_prior_sd = options.varying_law_prior_sd;
    problem.stiffness_node_s = options.varying_law_node_s;
    problem.stiffness_walk_sd = options.varying_law_walk_sd;
    problem.stiffness_with_effects = true;
    // Part of the null model, not a choice against the law as given.
    options.smoother.stiffness_gnss_margin = std::numeric_limits<double>::infinity();
  }
  Diagnosis d;
  d.log = log.directory;
  d.model_effects = model.effects;
  BatchSmootherOptions smoother = options.smoother;
  smoother.filter.ekf.record_innovations = true;
  smoother.threads = options.threads;  // the chain solver's solution is the same on any number
  d.solution = SmoothBatch(log, model, smoother);
  for (const auto& [name, series] : d.solution.ekf.stats.innovations) {
    InnovationReport f;
    f.name = name;
    f.updates = series.normalized.size();
    size_t inside = 0;
    for (double z : series.normalized) {
      f.nis_mean += z * z;
      inside += std::abs(z) <= 1.96;
    }
    if (f.updates > 0) f.nis_mean /= f.updates, f.inside_95 = double(inside) / f.updates;
    f.whiteness = LjungBox(series.normalized, std::min<int>(options.whiteness_lags, f.updates / 4));
    f.white = f.whiteness.p_value >= options.alpha;
    d.filter.push_back(f);
  }
  d.noise_scales = TestNoiseScales(d.solution.ekf.stats, options.alpha);
  // The innovation series stay in d.solution.ekf.stats for diagnose --series.
  d.used_fallback = d.solution.used_fallback;
  d.trust = CheckTrust(log, d.solution.estimates);
  d.notes = d.solution.notes;
  d.fitted_effects = d.solution.effects;
  d.corrected = options.corrected;
  if (d.used_fallback) {
    d.notes.push_back("the smoother failed: residuals are evaluated at the EKF's estimates");
  }
  d.residuals = EvaluateModelResiduals(log, model, d.solution, options.smoother);
  const ModelResiduals& m = d.residuals;

  std::vector<Series> series;
  for (const StreamResiduals& s : m.streams) series.push_back({s.name, s.t, s.normalized});
  Series force{"force_balance", {}, {}};
  force.r = ForceBalance(m, &force.t);
  series.push_back(force);
  for (const Series& s : series) d.streams.push_back(ReportStream(s.name, s.r, options));
  d.failures = FindFailures(series, m, options);

  std::vector<const EffectSignature*> candidates;
  for (const EffectSignature& s : registry.signatures()) {
    const bool corrected = std::any_of(options.corrected.begin(), options.corrected.end(),
                                       [&](const EffectEstimate& e) { return e.name == s.effect; });
    if (!corrected &&
        std::find(model.effects.begin(), model.effects.end(), s.effect) == model.effects.end()) {
      candidates.push_back(&s);
    }
  }
  const auto most_evident = [](const CandidateScore& a, const CandidateScore& b) {
    if (a.p_value != b.p_value) return a.p_value < b.p_value;
    return a.statistic / std::max(1, a.dof) > b.statistic / std::max(1, b.dof);
  };
  // Each candidate's test reads the residuals and the graph only: they run at once.
  d.candidates.resize(candidates.size());
  RunConcurrently(candidates.size(), options.threads, [&](size_t i) {
    CandidateScore& c = d.candidates[i];
    c = Score(*candidates[i], registry, m, log, model);
    c.p_value = std::min(1.0, c.p_value * candidates.size());
    c.significant = c.dof > 0 && c.p_value < options.alpha;
  });
  std::stable_sort(d.candidates.begin(), d.candidates.end(), most_evident);
  FitAndCompare(log, model, d.solution, options, registry, candidates.size(), &d.candidates);
  std::stable_sort(d.candidates.begin(), d.candidates.end(), most_evident);
  for (CandidateScore& c : d.candidates) {
    SetDetectable(options.alpha, candidates.size(), &c);
    const EffectSignature* signature = registry.FindSignature(c.effect);
    if (c.dof > 0 && signature != nullptr && signature->plausible) {
      c.implausible = ImplausibleBy(signature->plausible(log), c);
    }
  }
  // The model's own effects through their signatures: what is left of each once it is in.
  for (const EffectSignature& s : registry.signatures()) {
    const bool in_model =
        std::find(model.effects.begin(), model.effects.end(), s.effect) != model.effects.end() ||
        std::any_of(options.corrected.begin(), options.corrected.end(),
                    [&](const EffectEstimate& e) { return e.name == s.effect; });
    if (in_model) d.in_model.push_back(Score(s, registry, m, log, model));
  }
  // A force along the path the model lacks, whatever its shape, and what is left of it once the
  // best candidate is taken out; its local stretches are failures too.
  const CandidateScore* best = BestExplanation(d.candidates);
  Eigen::VectorXd best_column;
  if (best != nullptr && best->graph_column && m.graph != nullptr && m.graph->ok()) {
    best_column = best->graph_column(*m.graph);
  }
  d.path_force = TestForceAlongPath(m, best_column.size() > 0 ? &best_column : nullptr,
                                    best_column.size() > 0 ? best->effect : "", options.alpha);
  for (const PathForceTest::Stretch& stretch : d.path_force.stretches) {
    if (std::isnan(stretch.t_start) || std::isnan(stretch.t_end)) continue;
    FailureSegment f{stretch.t_start, stretch.t_end, {"force_along_path"}};
    SetConditions(m, &f);
    d.failures.push_back(f);
  }
  std::sort(d.failures.begin(), d.failures.end(),
            [](const FailureSegment& a, const FailureSegment& b) { return a.t_start < b.t_start; });
  const bool path_force = d.path_force.tested && d.path_force.p_value < options.alpha;
  bool failing = !d.failures.empty() || path_force;
  for (const StreamReport& s : d.streams) failing = failing || !s.consistent;
  const bool any = best != nullptr;
  // A significant candidate explains the misfit unless the force along the path stays
  // significant once its direction is taken out (only known for a candidate on the graph).
  const bool left_over = path_force && !std::isnan(d.path_force.after_p_value) &&
                         d.path_force.after_p_value < options.alpha;
  d.explained = (any || !failing) && !left_over;

  if (!log.truth.empty()) {
    // The simulator's disturbance is every external force; with drag, turn slip or sinkage in
    // the model the estimate's a_dist no longer carries them, so they are added back.
    const std::vector<WardEstimate> estimates =
        DisturbanceWithEffects(d.solution, log, model, &registry.terms());
    const Evaluation e = Evaluate(log, EstimateTable(estimates));
    d.truth.available = true;
    d.truth.velocity_rmse = e.velocity_rmse;
    d.truth.disturbance_rmse = e.disturbance_rmse;
  }
  return d;
}

ExtendedModel AddEffects(const DriveLog& log, const ModelConfig& model, const Diagnosis& before,
                         const std::vector<std::string>& effects, const EffectRegistry& registry) {
  ExtendedModel out{log, model, before.corrected};
  for (const std::string& name : effects) {
    const EffectSignature* signature = registry.FindSignature(name);
    const EffectTerm* term = registry.FindTerm(name);
    if (term != nullptr) {
      if (term->acts_on_windows) {
        // A term on windows: where the diagnosis found the effect (a patch, a change).
        const auto it = std::find_if(before.candidates.begin(), before.candidates.end(),
                                     [&](const CandidateScore& c) { return c.effect == name; });
        if (it == before.candidates.end() || it->windows.empty()) {
          throw std::invalid_argument("effect '" + name +
                                      "' acts on part of the drive, and the diagnosis found "
                                      "none to add it on");
        }
        for (const auto& [t0, t1] : it->windows) {
          out.model.effect_windows.push_back({name, t0, t1});
        }
      }
      if (std::find(out.model.effects.begin(), out.model.effects.end(), name) ==
          out.model.effects.end())
        out.model.effects.push_back(name);
    } else if (signature != nullptr && signature->correct) {
      const auto it = std::find_if(before.candidates.begin(), before.candidates.end(),
                                   [&](const CandidateScore& c) { return c.effect == name; });
      if (it == before.candidates.end()) continue;  // already corrected
      signature->correct(it->magnitude, &out.log);
      out.corrected.push_back({name, it->magnitude, it->magnitude_sd});
    } else {
      std::string usable;
      for (const EffectSignature& s : registry.signatures()) {
        if (registry.CanAdd(s.effect)) usable += " " + s.effect;
      }
      throw std::invalid_argument("effect '" + name +
                                  "' has neither a smoother term nor a measurement correction "
                                  "yet; usable:" +
                                  usable);
    }
  }
  return out;
}

ExtendedDiagnosis DiagnoseWith(const DriveLog& log, const ModelConfig& model,
                               const Diagnosis& before, const std::vector<std::string>& effects,
                               const DiagnosisOptions& options) {
  const EffectRegistry& registry =
      options.effects != nullptr ? *options.effects : EffectRegistry::Catalogue();
  ExtendedDiagnosis out{AddEffects(log, model, before, effects, registry), {}};
  DiagnosisOptions after = options;
  after.corrected = out.extended.corrected;
  out.after = Diagnose(out.extended.log, out.extended.model, after);
  return out;
}

}  // namespace slipgraph
