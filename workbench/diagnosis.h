// The workbench's diagnosis of a model on a log: the batch smoother's solution, each measurement
// stream's residuals against the model (RMS, chi-square consistency, Ljung-Box whiteness), the
// time segments where they break their bounds, and every catalogue effect not in the model scored
// by its signature test (workbench/effect_signatures.h), ranked, with "no candidate explains it"
// when none is significant.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "evaluation/evaluation.h"
#include "io/drive_log.h"
#include "model/model_config.h"
#include "solvers/batch_smoother.h"
#include "solvers/trust_check.h"
#include "workbench/effect_signatures.h"
#include "workbench/model_residuals.h"
#include "workbench/noise_scale.h"
#include "workbench/path_force_test.h"
#include "workbench/robust_statistics.h"

namespace slipgraph {

struct DiagnosisOptions {
  // One fixed problem per model (no re-gating of weak constraint 2 by the solution's own slip):
  // the fit-and-compare tests difference the costs of two solves of the same problem.
  // Every finite GNSS fix in the problem (no gate): a misfit the gate would leave out, such as
  // averaged fixes during acceleration, is what the workbench looks for.
  BatchSmootherOptions smoother = [] {
    BatchSmootherOptions o;
    o.regate_decay_prior = false;
    o.problem.gnss_gate_chi2 = std::numeric_limits<double>::infinity();
    // From the paper's filter, without the GNSS fading memory (EkfOptions::gnss_fading_*): the
    // workbench's figures (docs/workbench.md) were measured from it. From the fading filter
    // (diagnose_monte_carlo --gnss-fading) the rankings are the same on 5 seeds of the hidden
    // suite and on 3 of the mismatch suite, but on data/hidden_clock_offset a candidate that is
    // not hidden scores higher (sinkage resistance 49 -> 63; the problem takes its start and
    // weak constraint 2's gating from the filter).
    o.filter.ekf.gnss_fading_fixes = 0.0;
    o.filter.papers_accel_bias = true;  // and its accelerometer bias
    return o;
  }();
  double alpha = 0.01;      // family-wise level of the candidate tests and the segment tests
  double window_s = 2.0;    // segment test window
  int whiteness_lags = 20;  // Ljung-Box lags
  // Sensor effects already corrected in the log's measurements (AddEffects): not candidates.
  std::vector<EffectEstimate> corrected;
  // Fit and compare: every candidate that has a smoother term (or the best this many of them
  // by the score tests; 0: none) is fitted, the smoother re-solved with the term on, and tested
  // by the likelihood ratio 2 (C_0 - C_1) instead (CandidateScore). Score tests are local, at
  // the solution without the effect; where two candidates explain the same misfit in part (a
  // terrain change and slope slip on a drive whose hill comes after the change) the fit tells
  // them apart.
  int fit_candidates = -1;
  // Threads: the solution's solve, then the candidates tested and fitted at once (each test
  // reads the solution only, each fit is one single-threaded solve from it). The results do not
  // depend on the count where the batch's chain solver solves (Ceres, where the problem is not a
  // chain, sums per thread).
  int threads = 2;
  // A fit starts one term away from the solution: Gauss-Newton-sized steps at once
  // (BatchSmootherOptions::initial_trust_region_radius): 2-5 iterations against 7-9 at Ceres's
  // default on the bundled log.
  double fit_initial_trust_region_radius = 1e8;
  // The effects to test and their smoother terms; null: EffectRegistry::Catalogue(). Not owned.
  // The smoother runs with its terms (smoother.problem.effect_terms is set from it).
  const EffectRegistry* effects = nullptr;
  // A null model whose tire law varies slowly along the path, so that a patch of softer soil is
  // not read as a missing effect: the law's slip stiffness as a walk of nodes every
  // varying_law_node_s (WardProblemOptions::stiffness_*: this prior sd on the first node, this
  // walk density between them) in every solve, and the nodes among the score tests' nuisance
  // parameters. These set smoother.problem's stiffness_* (and stiffness_with_effects) and leave
  // out the smoother's check of the walk against the law as given (stiffness_gnss_margin): the
  // walk is the null model here, not a choice. 0: the law as given (the default;
  // docs/workbench.md: on the mismatch suite the walk trades one false finding for another).
  double varying_law_prior_sd = 0.0;
  double varying_law_node_s = 20.0;
  double varying_law_walk_sd = 0.1 / std::sqrt(20.0);  // 0.1 over 20 s, 1/sqrt(s)

  bool IsValid(std::string* error) const;
};

struct StreamReport {
  std::string name;
  size_t samples = 0;
  double rms = 0.0;           // of the normalized residuals (1 when the model's sd is right)
  double chi_square_p = 1.0;  // upper tail of sum r^2 under chi-square(samples)
  bool consistent = true;     // chi_square_p >= alpha
  WhitenessTest whiteness;
  bool white = true;  // whiteness.p_value >= alpha
};

// The EKF's consistency on one measurement: its normalized innovations (ward_ekf.h), which a
// consistent filter makes white with unit variance.
struct InnovationReport {
  std::string name;
  size_t updates = 0;
  double nis_mean = 0.0;   // mean normalized innovation squared (1 when consistent)
  double inside_95 = 0.0;  // fraction with |z| <= 1.96
  WhitenessTest whiteness;
  bool white = true;
};

struct FailureSegment {
  double t_start = 0.0, t_end = 0.0;
  std::vector<std::string> streams;
  // Operating conditions there (means over the segment; terrain when the log's truth has it).
  double speed_mps = 0.0, abs_pitch_rad = 0.0, abs_yaw_rate_radps = 0.0;
};

struct SeriesScore {
  std::string stream;
  SlopeFit fit;
};

struct CandidateScore {
  std::string effect;
  std::string test;
  std::string where;  // the chosen patch or change point, when the test searched
  std::vector<std::pair<double, double>> windows;  // its time spans (effect_signatures.h)
  // ((|magnitude| - negligible) / magnitude_sd)^2: chi-square, 1 dof, under the null
  // |theta| <= negligible (workbench/effect_signatures.h).
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;  // Bonferroni-adjusted for the search and the candidates scored
  bool significant = false;
  double magnitude = 0.0, magnitude_sd = 0.0;  // precision-weighted over the series
  // How `--with` adds it: "smoother term", "measurement correction", or "" (not yet).
  std::string added_as;
  std::vector<SeriesScore> series;
  // The tested term's raw column on the graph, when the test was on the graph.
  std::function<Eigen::VectorXd(const GraphProjector&)> graph_column;
  double searched = 1.0;    // the search's multiplier on a single test's p-value (scans)
  double dispersion = 1.0;  // robust over model-based variance of the score (>= 1)
  // Fit and compare (DiagnosisOptions::fit_candidates): the smoother re-solved with the term
  // on, 2 (C_0 - C_1) of the solutions' costs, and the fitted magnitude (which then is the
  // candidate's magnitude). A fitted candidate's statistic is the likelihood ratio over the
  // dispersion (a quasi-likelihood ratio, chi-square with 1 dof under the null) and its p-value
  // that statistic's, with the same search and Bonferroni multipliers; the score test's are kept
  // beside them.
  bool fitted = false;
  double likelihood_ratio = 0.0;
  double score_statistic = 0.0, score_p_value = 1.0, score_magnitude = 0.0,
         score_magnitude_sd = 0.0;
  // The smallest |magnitude| this log would show as significant (at DiagnosisOptions::alpha,
  // with this candidate's search and Bonferroni multipliers) with 80 % power, from the test's
  // own sd: below it, "not significant" says the log cannot tell, not that the effect is absent.
  // NaN when the candidate was not tested.
  double detectable = std::numeric_limits<double>::quiet_NaN();
  double negligible = 0.0;  // the test's null |theta| <= negligible (effect_signatures.h)
  // The sd the candidate's test divides by: magnitude_sd, widened by the dispersion once fitted
  // (its statistic is the likelihood ratio over the dispersion).
  double test_sd() const { return fitted ? magnitude_sd * std::sqrt(dispersion) : magnitude_sd; }
  // Why the magnitude is physically implausible for this vehicle on this log (empty: plausible;
  // EffectSignature::implausible). An implausible candidate is not offered as the fix.
  std::string implausible;
};

// The first candidate (best first) that is significant and plausible: what the diagnosis offers
// as the missing effect, and what `--add-best` adds. nullptr when there is none.
const CandidateScore* BestExplanation(const std::vector<CandidateScore>& candidates);

struct TruthErrors {
  bool available = false;
  double velocity_rmse = 0.0, disturbance_rmse = 0.0;
};

struct Diagnosis {
  std::string log;
  std::vector<std::string> model_effects;
  std::vector<StreamReport> streams;
  std::vector<InnovationReport> filter;  // the EKF front end's innovations, per measurement
  // Each measurement's stated noise tested from those innovations: a noise stated too small is
  // a parameter off, not a missing force (workbench/noise_scale.h).
  std::vector<NoiseScaleFinding> noise_scales;
  std::vector<FailureSegment> failures;
  std::vector<CandidateScore> candidates;  // best first
  // The effects already in the model (terms or corrections) scored by their own signatures,
  // unadjusted: what is left of each in the residuals.
  std::vector<CandidateScore> in_model;
  // Any force along the path the model lacks (the omnibus test), and what is left of it after
  // the best candidate (workbench/path_force_test.h).
  PathForceTest path_force;
  // false: failures, a rejected stream or a force along the path, and no significant candidate
  // that takes it away.
  bool explained = true;
  TruthErrors truth;
  std::vector<EffectEstimate> fitted_effects;  // the model's own effects, as the smoother fit them
  std::vector<EffectEstimate> corrected;       // sensor effects corrected in the log
  bool used_fallback = false;
  // The solution against the log's own wheels and GNSS (solvers/trust_check.h): a diagnosis of
  // an untrusted solution may blame the wrong effect.
  TrustReport trust;
  std::vector<std::string> notes;
  ModelResiduals residuals;  // for plots
  SmootherResult solution;   // for plots; its EKF run keeps the innovation series
};

Diagnosis Diagnose(const DriveLog& log, const ModelConfig& model,
                   const DiagnosisOptions& options = {});

// The loop's second half: `effects` switched on, each as a smoother term (added to
// model.effects) or, for an effect that lives in a sensor, as a correction of the log's
// measurements by the magnitude `before` fitted (effect_signatures.h). Throws
// std::invalid_argument for a name outside the catalogue or an effect with neither.
struct ExtendedModel {
  DriveLog log;
  ModelConfig model;
  std::vector<EffectEstimate> corrected;
};
ExtendedModel AddEffects(const DriveLog& log, const ModelConfig& model, const Diagnosis& before,
                         const std::vector<std::string>& effects,
                         const EffectRegistry& registry = EffectRegistry::Catalogue());

// The diagnosis of the model extended by `effects` (AddEffects, with the registry of
// `options.effects`), as `diagnose --with` and Python's diagnose(with_effects=...) report it.
struct ExtendedDiagnosis {
  ExtendedModel extended;
  Diagnosis after;
};
ExtendedDiagnosis DiagnoseWith(const DriveLog& log, const ModelConfig& model,
                               const Diagnosis& before, const std::vector<std::string>& effects,
                               const DiagnosisOptions& options);

}  // namespace slipgraph
