// Online estimation: a fixed-lag sliding-window smoother behind the EKF. The window holds the
// states of the last `window_s` seconds (Ward model, the same factors as the batch problem, from
// WardFactorSource) and the IMU offsets; every `update_every` wheel samples it takes the new
// states (initialised from the EKF), solves with a bounded number of Gauss-Newton iterations,
// and marginalizes the states older than the window into a MarginalPrior (Schur complement), so
// their information stays. A state's refined estimate is final when it leaves the window: its lag
// is the time from the sample to that moment.
//
// Failures: a solve that is not usable restores the pre-solve values; states that leave a failed
// window are reported with the EKF's estimate (flagged), are never marginalized, and the window
// restarts from an EKF prior on its new oldest state. A rejected solve (reject_distance_sd) is
// handled as a failed one, its states set to the EKF's estimates. Every such event is counted and
// noted.
//
// Causality: a state's factors include the IMU samples nearest to it, up to half a wheel cycle
// after it, so the window runs one wheel cycle behind the newest sample.
#pragma once

#include <string>
#include <vector>

#include "evaluation/progress.h"
#include "io/drive_log.h"
#include "io/estimate_file.h"
#include "model/model_config.h"
#include "problems/ward_factor_source.h"
#include "solvers/batch_smoother.h"
#include "solvers/ekf_runner.h"

namespace slipgraph {

// How each window update is solved. kCeres: ceres::Solve (Levenberg-Marquardt, sparse normal
// Cholesky). kChainGaussNewton: Gauss-Newton steps on the window's own structure (a chain of
// states with the IMU offsets as a border, solvers/chain_covariance.h), each residual block's
// cost function called once a step; the marginal covariances come from the same
// factorization. A step that raises the cost is undone and that update falls back to Ceres.
// kChainLevenbergMarquardt: the batch's solver on the same structure (solvers/chain_solver.h),
// to convergence within max_iterations, Ceres where it fails; for chunks of minutes, which start
// from the front end and need more than a step.
enum class WindowSolver { kCeres, kChainGaussNewton, kChainLevenbergMarquardt };

struct WindowSmootherOptions {
  double window_s = 2.0;  // states further than this behind the newest are marginalized
  int update_every = 10;  // wheel samples between window solves (10 Hz at 100 Hz wheels)
  // Bounded work per update. One Gauss-Newton step from the previous update's solution (the new
  // states from the front end) gave the same estimates as five on the ward21 and ward21m suites
  // (docs/smoother.md) at a fifth of the latency.
  int max_iterations = 1;
  bool covariance = true;  // marginal sd of each state as it leaves (else the EKF's sd)
  // Add to that sd the tire law's uncertainty as the front end sees it (the bank's spread of the
  // soils' estimates, or the single filter's shift with the law's slope: FilterResult::
  // law_spread_sd; none without either). The window's own covariance takes the law as exact;
  // the batch computes the smoother's own sensitivity to the law instead
  // (BatchSmootherOptions::consider_law_uncertainty).
  bool law_spread_in_sd = true;
  // Take at each state the law the front end's bank weighed there (FilterResult::law): the
  // window then refines the bank's estimate under the bank's own law. false, or one filter: the
  // model's law everywhere.
  bool law_from_front_end = true;
  // Let the disturbance walk at each step with the density the front end's prediction took there
  // (its adaptive w3, FilterResult::disturbance_density): where the accelerometer disagrees with
  // the model the filter lets its disturbance move faster, and the window, held to the model's
  // w3, put the same unexplained force in the velocity. false: the model's w3 everywhere.
  bool disturbance_from_front_end = true;
  // The front end's wheels' checks on its accelerometer bias as factors, each at the state where
  // its interval closed (BatchSmootherOptions::bias_from_front_end).
  bool bias_from_front_end = true;
  // The tire law's slip stiffness as a slowly varying unknown (WardProblemOptions::stiffness_*,
  // the batch's walk) with this prior sd around that law, when the model lists its soils
  // (law_samples: the user says the terrain's law varies, and by how much). Without soils the
  // law is taken as given, as the front end takes it; 0: always. Overrides
  // problem.stiffness_prior_sd.
  double stiffness_prior_sd = 0.15;
  // Weak constraint 3 on the velocity (WardProblemOptions::no_pull_back_sd_density, m/s
  // sqrt(s)): the body does not move against its wheels unless gravity pulls it back. Without
  // it, the window's velocity sat 3-7 cm/s below zero through hold-backs on ward21m (the
  // accelerometer integrated over an attitude error), where the EKF's weak constraint 3 holds
  // its own near zero. A spring tether's recoil does pull the robot back (fig5: -5 cm/s for a
  // few tenths of a second), which a stronger prior flattens. Chosen on ward21 and ward21m seeds
  // 1-4 and the bundled logs (0.0005-0.05; docs/smoother.md). 0: off. Overrides
  // problem.no_pull_back_sd_density.
  double no_pull_back_sd_density = 0.005;
  // A solve that moves the window's velocity far from the front end's is rejected unless the
  // velocity measurements in the window (GNSS, another estimator's) fit it better than the front
  // end's estimate: far is an RMS over the window's states of the difference above this many of
  // the front end's sd (a smoother's estimate differs from its filter's by less than the filter's
  // sd). Rejected, the window's states go back to the front end's estimates, its leaving states
  // keep the front end's (from_filter) and, where states left, it restarts from a front-end prior
  // on its new oldest state. 0: never.
  double reject_distance_sd = 3.0;
  WindowSolver solver = WindowSolver::kChainGaussNewton;
  // kChainLevenbergMarquardt's: its residual evaluation's threads and its stopping rules
  // (ChainSolverOptions: a step within this of the solution's sd, the cost's relative change).
  int threads = 1;
  double step_sd_tolerance = 0.01;
  double function_tolerance = 1e-10;
  FilterRunOptions filter;
  WardProblemOptions problem;
  double min_immobilized_s = 0.1;  // as the batch smoother's post-processing detection
  // Told after each update (done of total), as `progress_stage` ("chunk" in chunked mode).
  ProgressCallback progress;
  std::string progress_stage = "window update";
  // Keep the front end's estimates in the result (WindowSmootherResult::ekf.estimates) beside the
  // window's. False (the chunked mode): the front end's estimates become the result's estimates,
  // each replaced by the window's as its state leaves, and ekf.estimates is left empty: one
  // estimate per sample held instead of two, on a log of hours.
  bool keep_front_end_estimates = true;
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};

struct WindowSmootherResult {
  // One per wheel sample: the window's estimate as it left (or the EKF's, see from_filter).
  std::vector<WardEstimate> estimates;
  std::vector<double> lag_s;      // newest state time when the estimate became final, minus t
  std::vector<bool> from_filter;  // true: the window failed there and the EKF estimate stands
  FilterResult ekf;               // the streaming front end, at every sample
  long updates = 0, failed_updates = 0, unconverged_updates = 0, failed_marginalizations = 0;
  long covariance_failures = 0;
  long chain_fallbacks = 0;   // chain-solver updates that Ceres had to solve
  long rejected_updates = 0;  // solves rejected (WindowSmootherOptions::reject_distance_sd)
  // Per update that solved (with reject_distance_sd > 0): the velocity's RMS distance from the
  // front end's in the front end's sd.
  std::vector<double> update_distance_sd;
  // Per update: solve and marginalization, wall time (with kChainGaussNewton the leaving states'
  // covariance too: it comes from the solve's factorization).
  std::vector<double> update_ms;
  std::vector<double> covariance_ms;  // per update: marginal covariance of the leaving states
  FactorCounts counts;                // the factors that went in (and measurements too late)
  // The tire law's slip-stiffness scale theta at each node of its walk, as each node left the
  // window (WardProblemOptions::stiffness_prior_sd; empty when off).
  std::vector<double> stiffness;
  std::vector<std::string> notes;
};

// Runs the front end (options.filter) over the log, then the window behind it.
WindowSmootherResult SmoothWindowed(const DriveLog& log, const ModelConfig& model,
                                    const WindowSmootherOptions& options = {});
// The window behind a front end's run over the same log (`ekf`, run with options.filter's
// settings): a caller that has the run (compare) passes it down instead of running it again.
// The run is kept in the result (WindowSmootherResult::ekf): pass it with std::move where the
// caller has no further use for it, so that a long log holds one copy of it.
WindowSmootherResult SmoothWindowed(const DriveLog& log, const ModelConfig& model, FilterResult ekf,
                                    const WindowSmootherOptions& options = {});

// Chunked batch mode for logs too long for one problem: the window machinery with chunks of
// `chunk_min` minutes solved to convergence, each state final once `overlap_s` of later data has
// been seen (its lag), older states marginalized into the prior that joins the chunks. Memory is
// bounded by one chunk plus the overlap. Weak constraint 2 keeps the EKF's gate here (the batch's
// re-gating, BatchSmootherOptions::regate_decay_prior, needs a whole first solution).
// wheel_rate_hz: the log's wheel-sample rate (states per second).
WindowSmootherOptions ChunkedOptions(double chunk_min, double overlap_s, double wheel_rate_hz,
                                     const BatchSmootherOptions& batch);

std::string DescribeWindowRun(const WindowSmootherResult& result);

// The columns `online` adds to the estimate file (docs/estimate-file.md), per estimate: the front
// end's own at the same sample (ekf_v_bx, ekf_sd_v_bx, ekf_a_dist, ekf_sd_a_dist, ekf_slip_ema,
// ekf_immobilized), lag_s (when the refined estimate became final) and from_filter (1 where a
// failed window left the front end's estimate). Without the front end's estimates kept
// (WindowSmootherOptions::keep_front_end_estimates) only lag_s and from_filter.
std::vector<ExtraColumn> OnlineColumns(const WindowSmootherResult& result);

}  // namespace slipgraph
