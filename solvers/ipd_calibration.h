// Online slip-model identification by Integrated Perturbative Dynamics (Rogers-Marcovitz,
// Seegmiller & Kelly). The log is cut into overlapping path segments between pose measurements
// (2 s long, one starting every `spacing_s`); each segment's end pose is predicted from odometry,
// the measured roll/pitch and the current slip parameters alpha (factors/ipd_segment.h) and,
// when the segment ends, compared with the measured relative pose:
//
// - systematic: an identification EKF on the 13 alpha (eqs. 28-34): alpha constant plus a
//   random walk (so terrain changes are followed), H = d h / d alpha by automatic
//   differentiation, R = R_sys of eq. (15) with the current Q;
// - stochastic: a linear Kalman filter on the diagonal of Q (eqs. 18-27): the observation is the
//   residual's scatter matrix r r' (6 unique entries), its model R_sys(q) is linear in q with the
//   Jacobian of eq. (21), and its noise follows eqs. (26)-(27) for a zero-mean Gaussian residual.
//
// Every prediction is scored *before* its segment updates the filters (online), against the
// no-slip model (alpha = 0): along-track, cross-track and heading errors of the 2 s prediction.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "factors/ipd_segment.h"
#include "io/drive_log.h"
#include "solvers/jump_detector.h"

namespace slipgraph {

// The terrain memory (solvers/ipd_terrain_memory.h): slip models of earlier terrains, recalled
// when the segments say the robot is back on one.
struct IpdTerrainMemoryOptions {
  int capacity = 8;                 // stored models (0: off)
  double settle_s = 30.0;           // a model is stored only after this long in use
  double search_s = 20.0;           // stored models are scored this long after a misfit
  int window = 4;                   // segments in the likelihood comparison
  double log_bayes_factor = 4.605;  // ln(100)
};

// Jump detection on the segments' innovations (solvers/jump_detector.h): a terrain change is a
// jump in alpha that the slow walk follows in tens of seconds and that seldom fails the gate of
// one segment; the detector tests "alpha jumped before segment k" for the recent segments.
struct IpdJumpOptions {
  bool enabled = true;
  double jump_sd = 0.05;          // prior sd of a jump in each alpha
  double log_bayes_factor = 6.9;  // ln 1000
  double window_s = 20.0;         // jumps this far back are tested
};

struct IpdOptions {
  double segment_s = 2.0;  // path segment length (prediction horizon)
  double spacing_s = 0.5;  // a new segment starts this often (segments overlap)
  double gravity_mps2 = 9.80665;
  double alpha_prior_sd = 0.5;   // initial sd of each alpha (alpha starts at 0, as the paper)
  double alpha_walk_sd = 0.001;  // random walk of each alpha per sqrt(s): slow drift
  Eigen::Vector3d q_initial{1e-3, 1e-3, 1e-3};  // initial Q diagonal ((m/s)^2 s, ..., (rad/s)^2 s)
  double q_prior_sd = 1e-3;                     // initial sd of each q
  double q_walk_sd = 1e-5;                      // random walk of each q per sqrt(s)
  bool calibrate_q = true;
  double min_pose_sd_m = 0.005;  // floor for the measured poses' stated sd
  // After this many gated segments in a row the next one is taken, alpha's covariance doubled
  // until it passes the gate (fading memory: the model, not a pose, is wrong — a terrain
  // change). 0: never.
  int readmit_after = 1;
  // The reported prediction covariance matched to the recent errors
  // (solvers/ipd_covariance_matching.h), with a memory of this many predictions, by the EKF, the
  // window and the batch; 0: off.
  double match_covariance_segments = 20.0;
  IpdTerrainMemoryOptions terrain_memory;
  IpdJumpOptions jump;
  // Each field in its range, the terrain memory's and the jumps' too; the first that is not
  // is named in *error.
  bool IsValid(std::string* error) const;
};

// The segments' innovation gate: chi-square with 3 dof at 99.99 % (a pose glitch must not wreck
// the model). The EKF and the Ceres window both test against it.
constexpr double kSegmentGateChi2 = 21.1;

// One path segment: odometry steps between two pose measurements, and their relative pose.
struct IpdSegment {
  double t_start = 0.0, t_end = 0.0;
  std::vector<ipd::OdometryStep> steps;
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();  // rho_start^-1 (+) rho_end
  Eigen::Matrix3d sigma_start = Eigen::Matrix3d::Zero(), sigma_end = Eigen::Matrix3d::Zero();
};

// Throws InputError-like std::invalid_argument when the log lacks wheels or pose.
std::vector<IpdSegment> BuildIpdSegments(const DriveLog& log, const IpdOptions& options);

// Error of one 2 s prediction: measured minus predicted, position split along and across the
// predicted displacement (along the start heading when it is shorter than 1 cm).
struct PredictionError {
  double t_start = 0.0;
  double along_m = 0.0, cross_m = 0.0, heading_rad = 0.0;
  Eigen::Matrix3d predicted_covariance = Eigen::Matrix3d::Zero();  // R_sys with the current Q
  // The share of predicted_covariance from alpha's own uncertainty (H P H'; 0 for a fixed alpha).
  Eigen::Matrix3d parameter_covariance = Eigen::Matrix3d::Zero();
};

PredictionError EvaluatePrediction(const IpdSegment& segment, const double* alpha,
                                   const IpdOptions& options, const Eigen::Vector3d& q);

// A segment's prediction at alpha, linearized: the predicted end pose, its residual (measured
// minus predicted, heading wrapped) and H = d h / d alpha (3 x 13), from one integration with
// automatic differentiation.
struct SegmentLinearization {
  Eigen::Vector3d predicted = Eigen::Vector3d::Zero();
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, ipd::kAlphaSize> H;
};
SegmentLinearization LinearizeSegment(const IpdSegment& segment, const double* alpha,
                                      const IpdOptions& options);
// H P H' of a segment's prediction in its (along, cross, heading) axes: what the uncertainty of
// alpha adds to the predicted covariance.
Eigen::Matrix3d ParameterCovariance(
    const IpdSegment& segment, const double* alpha,
    const Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize>& P, const IpdOptions& options);

struct PredictionStats {
  size_t segments = 0;
  double mean_position_error_m = 0.0;
  double sd_along_m = 0.0, sd_cross_m = 0.0;
  double mean_heading_error_rad = 0.0;
  double sd_heading_rad = 0.0;
  // Mean predicted covariance against the sample covariance of (along, cross, heading), per
  // diagonal entry: predicted / sample (1 = calibrated).
  Eigen::Vector3d predicted_over_sample = Eigen::Vector3d::Constant(std::nan(""));
};
PredictionStats Summarize(const std::vector<PredictionError>& errors);
// The predictions that start a minute or more after the first: while alpha still has its prior
// sd (0.5), a few predictions are metres uncertain and their variance dominates the mean.
std::vector<PredictionError> AfterTheFirstMinute(const std::vector<PredictionError>& all);

struct IpdCalibrationResult {
  std::vector<IpdSegment> segments;
  std::vector<PredictionError> no_slip;     // alpha = 0
  std::vector<PredictionError> calibrated;  // alpha as known when the segment started
  std::vector<double> update_t;             // time of each update (a segment's end)
  std::vector<std::array<double, ipd::kAlphaSize>> alpha;  // after each update
  std::vector<Eigen::Vector3d> q;                          // after each update
  std::array<double, ipd::kAlphaSize> final_alpha{};
  std::array<double, ipd::kAlphaSize> final_alpha_sd{};
  Eigen::Vector3d final_q = Eigen::Vector3d::Zero();
  std::vector<std::string> notes;
};

IpdCalibrationResult CalibrateIpdEkf(const DriveLog& log, const IpdOptions& options = {});

// The jump detector's options from the IPD options (one hypothesis per segment over
// jump.window_s; each stretch of odometry is in segment_s / spacing_s segments).
JumpDetectorOptions IpdJumpDetectorOptions(const IpdOptions& options);

// The stochastic calibration of eqs. (18)-(27): a linear Kalman filter on the diagonal of Q whose
// observation is the scatter matrix of a segment's residual. Shared by the EKF and the Ceres
// calibrations.
class StochasticCalibrator {
 public:
  explicit StochasticCalibrator(const IpdOptions& options);
  // residual: measured minus predicted; terms: the segment's covariance terms at the current
  // alpha; parameter_covariance: H P H' of the alpha estimate (0 when unknown); elapsed: time
  // since the last update (random walk of q).
  void Update(const Eigen::Vector3d& residual, const ipd::PredictionCovarianceTerms& terms,
              const Eigen::Matrix3d& parameter_covariance, double elapsed_s);
  const Eigen::Vector3d& q() const { return q_; }
  // A recalled terrain's Q (solvers/ipd_terrain_memory.h); the estimate's covariance is kept.
  void Recall(const Eigen::Vector3d& q) { q_ = q; }

 private:
  IpdOptions options_;
  Eigen::Vector3d q_;
  Eigen::Matrix3d P_;
};

}  // namespace slipgraph
