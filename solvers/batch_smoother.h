// Post-processing: the whole-log Ward factor graph (problems/ward_batch_problem) solved on its
// chain structure (or by Ceres with sparse Cholesky), initialised from the EKF, with a standard
// deviation for every estimate from the marginal covariance. A failed or unusable solve falls back
// to the EKF's estimates and says so; nothing is dropped.
#pragma once

#include <ceres/solver.h>

#include <map>
#include <string>
#include <vector>

#include "evaluation/progress.h"
#include "io/drive_log.h"
#include "model/model_config.h"
#include "problems/ward_batch_problem.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {

// `options` with the choices of the EKF run that initialises the problem (GNSS on or off, the
// velocity model, the wheel-still threshold), so the smoother's factors and its filter agree.
WardProblemOptions WithFilterSettings(WardProblemOptions options, const FilterRunOptions& filter);

// The slip-stiffness prior (WardProblemOptions::stiffness_prior_sd) that post-processing front
// ends (`smooth`, `compare`, the Python module) use where the model lists its soils, unless told
// otherwise: a user's tire law is a fit that no terrain matches exactly. Chosen on ward21 seeds
// 1/2; on seeds 3/4, not used to choose it, the batch's velocity error fell 0.0172/0.0166 ->
// 0.0115/0.0114 m/s with the disturbance unchanged; where the law is exact (fig5) it costs 0.0031
// -> 0.0048 m/s.
constexpr double kPostProcessingStiffnessPriorSd = 0.15;
// The prior post-processing takes for a model when not told one (NaN `requested`): that one where
// the model lists its soils (ModelConfig::law_samples: the user says the terrain's law varies, and
// by how much), the law as given where it does not, as the window takes it. With one guessed law
// the estimated stiffness follows any error the model lacks: on ward21m, whose terrain is of
// another family than the law, the batch's velocity error was 0.027-0.029 m/s with it and
// 0.016-0.017 without, and where the law is exact it is biased low (docs/smoother.md). A given
// value is returned.
double PostProcessingStiffnessPriorSd(const ModelConfig& model, double requested);

// How the batch is solved. The chain (solvers/chain_solver): Levenberg-Marquardt on the
// block-tridiagonal information with the globals as its border, Ceres where the problem is not a
// chain (a note says so). Ceres: its trust region with sparse Cholesky (SuiteSparse).
enum class BatchSolver { kChain, kCeres };

struct BatchSmootherOptions {
  BatchSolver solver = BatchSolver::kChain;
  int max_iterations = 200;
  // Told after each solver iteration (its number and cost; no total, max_iterations is only a
  // bound).
  ProgressCallback progress;
  // Converged when a kept step lowers the cost by less than this fraction of it (Ceres' default
  // function tolerance), or by the step rule below, whichever comes first. Where robust losses
  // are past their bend (the disturbance at a hold-back) the solve then creeps: on a 10-minute
  // log 30 more iterations lower the cost by another 0.2 of 58 000 and move no velocity by more
  // than 0.03 sd, one disturbance by up to 2.7 sd (docs/benchmarks.md). 1e-12: to that optimum.
  double function_tolerance = 1e-6;
  // The chain solver's convergence (ChainSolverOptions::step_sd_tolerance): a step that would
  // move the solution by less than this in its own sd ends the solve.
  double step_sd_tolerance = 0.01;
  int threads = 1;
  // Ceres's initial trust-region radius (its default, 1e4, here). A solve that starts at a
  // solution of a nearby problem (`start`) can take Gauss-Newton-sized steps at once: the
  // workbench's fits, one term away from the solution, take 2-5 iterations at 1e8 against 7-9.
  double initial_trust_region_radius = 1e4;
  bool covariance = true;   // marginal sd per state (else the EKF's sd is reported)
  FilterRunOptions filter;  // the EKF run that initialises the smoother
  WardProblemOptions problem;
  // Post-processing detection: the smoothed slip (no EMA lag) above the threshold for at least
  // this long while the wheels turn and the robot is not braking.
  double min_immobilized_s = 0.1;
  // Start the solve from these states and offsets instead of the EKF's (one per wheel sample, as
  // a SmootherResult's estimates on the same log): a model refitted with one more term converges
  // from the previous solution in a few iterations. Ignored when the sizes differ.
  const std::vector<WardEstimate>* start = nullptr;
  // Weak constraint 2 (the disturbance decays while the wheels do not slip) is gated by a slip.
  // First solve: the EKF's slip EMA, which lags each hold-back's onset and, when the EKF's
  // velocity is biased by a tire law that is not the terrain's, stays below the gate through a
  // whole hold-back; the prior then pulls a_dist toward zero and the velocity up with it (seed 2
  // of ward21, run 19: +2.5 cm/s through a 3 s hold-back). With this on, a second solve, started
  // from the first, is gated by the first solve's own slip (WardProblemOptions::decay_gate_slip):
  // ward21 disturbance RMSE -10 to -11 %, velocity within +-3 %, onset delays shorter
  // (docs/smoother.md). Off for fit-and-compare (workbench/): its likelihood-ratio tests compare
  // two solves of one fixed problem.
  bool regate_decay_prior = true;
  // The front end's wheels' checks on its accelerometer bias as factors
  // (WardProblemOptions::accel_bias, when that is empty): where the model's slip persistence is on
  // (ModelConfig::slip_persistence), the smoother holds the bias the filter's checks measured.
  bool bias_from_front_end = true;
  // The tire law's stated uncertainty (ModelConfig::law_samples, else tire_sd and rolling_sd) in
  // every sd: for each soil law (its deviation over sqrt(n - 1)), or each coefficient with an sd
  // (one sd off), the problem is built again with the law so moved and evaluated at the
  // solution; the residuals' change, through the same factorization as the covariance, gives the
  // estimate's first-order shift dx, and the sum of dx dx' is added to the states' covariance (a
  // Schmidt consider covariance: the law is not refitted, its error is counted).
  bool consider_law_uncertainty = true;
  // The slip stiffness (WardProblemOptions::stiffness_prior_sd) checked against GNSS, the one
  // sensor that sees the velocity without the tire law: the log is smoothed again with the law
  // as given, and the stiffness's solution is kept unless its velocities fit GNSS worse by more
  // than this cost (half a chi-square; 3: a likelihood ratio of e^3 in favour of the law as
  // given). A law of another family, or an accelerometer error the model lacks (an AHRS's slow
  // attitude error), pulls the stiffness far down and the velocity below GNSS with it (ward21m,
  // docs/mismatch.md). Costs a second smooth. Infinity: no check.
  double stiffness_gnss_margin = 3.0;
  // The two solutions the check compares are two models GNSS tells apart by little (on ward21m
  // by a cost of -1 to +2 on most runs). With this on, the reported sd count the one not kept:
  // each state's variance becomes the mean squared error about the kept solution over both,
  // weighted by GNSS's likelihood ratio at even prior odds (solvers/model_choice_variance.h).
  // The estimates are unchanged.
  bool model_choice_variance = true;

  // The solver's settings (the filter's and the problem's are checked where they are used).
  bool IsValid(std::string* error) const;
};

// A model effect's estimated magnitude (factors/effect_term.h), in its term's unit.
struct EffectEstimate {
  std::string name;
  double value = 0.0;
  double sd = 0.0;  // NaN when the covariance was not recovered
};

struct SmootherResult {
  std::vector<WardEstimate> estimates;         // same layout as the EKF's, one per wheel sample
  FilterResult ekf;                            // the initialising filter run
  std::vector<EffectEstimate> effects;         // the model's effects that have a model term
  double final_cost = 0.0;                     // the solution's cost (for likelihood-ratio tests)
  std::map<std::string, double> cost_by_kind;  // the solution's cost per factor kind
  ceres::Solver::Summary summary;              // from either solver (BatchSolver)
  std::string solver;                          // the one that solved it (empty: none ran)
  bool used_fallback = false;                  // true: estimates are the EKF's (see notes)
  bool covariance_ok = false;
  // corr(v_bx error at k, at k+1) from the chain covariance (empty without it): how long the
  // solution's own velocity error persists.
  std::vector<double> velocity_next_correlation;
  // The tire law's slip-stiffness scale theta at each node of its walk (the law's slope times
  // 1 + theta; WardProblemOptions::stiffness_prior_sd; empty when off) and its sd.
  std::vector<double> stiffness, stiffness_sd;
  std::vector<std::string> notes;
};

// Runs the front end (options.filter) over the log, then smooths from its estimates.
SmootherResult SmoothBatch(const DriveLog& log, const ModelConfig& model,
                           const BatchSmootherOptions& options = {});
// Smooths from a front end's run over the same log (`ekf`, run with options.filter's settings
// and the same model but for its effects, which the front end does not model): a caller that has
// the run (compare, the workbench's fits) passes it down instead of running it again.
SmootherResult SmoothBatch(const DriveLog& log, const ModelConfig& model, const FilterResult& ekf,
                           const BatchSmootherOptions& options = {});

std::string DescribeSmootherRun(const SmootherResult& result);

// The estimates with the model's fitted external forces (the force terms but the model
// parameters': drag, turn slip, sinkage resistance; factors/effect_term.h) added to a_dist: the
// disturbance as every external force the tires and gravity do not explain, as a simulator's truth
// and a reader of `a_dist` count it. The solution's own a_dist leaves the modelled ones out (they
// are terms of their own). terms: the ones the smoother ran with (null: the catalogue's).
std::vector<WardEstimate> DisturbanceWithEffects(const SmootherResult& result, const DriveLog& log,
                                                 const ModelConfig& model,
                                                 const EffectTerms* terms = nullptr);

}  // namespace slipgraph
