// The IPD input noise Q = diag(q) of eq. (15) by maximum likelihood from the pose residuals the
// segments leave at a given alpha: issue 7's "Q by maximum likelihood", the batch calibration's
// alternative to the paper's online scatter-matrix filter (StochasticCalibrator, eqs. 18-27),
// which sees each residual once, at the alpha known before it.
//
// q differs by terrain, so it is one value per block of time, with a random walk on log q
// between consecutive blocks:
//
//   minimize  sum_k w (r_k' S_k^-1 r_k + log det S_k) / 2
//           + sum_b |log q_b+1 - log q_b|^2 / (2 walk_sd^2 block_s)
//           + |log q_0 - log q_prior|^2 / (2 prior_sd^2)
//   S_k = M_k + sum_j q_b(k),j B_k,j      (eq. 15's terms: poses M, the inputs' B_j)
//
// w: the share of its odometry a segment owns (spacing / segment length): overlapping segments
// share their odometry, so each counts that share, a quasi-likelihood. Solved on log q with
// Ceres' line-search minimizer (GradientProblem, L-BFGS) and the analytic gradient
//
//   d/d q_j of (r' S^-1 r + log det S) / 2 = (tr(S^-1 B_j) - r' S^-1 B_j S^-1 r) / 2,
//
// tested against central differences (tests/ipd_noise_likelihood_test.cpp).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "factors/ipd_segment.h"

namespace slipgraph {

struct NoiseLikelihoodSegment {
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();  // measured minus predicted relative pose
  ipd::PredictionCovarianceTerms terms;                // eq. (15)'s terms at the same alpha
  int block = 0;                                       // the q block it belongs to
};

struct NoiseLikelihoodOptions {
  double block_s = 5.0;        // a block's length (for the walk's variance)
  double log_q_walk_sd = 0.2;  // per sqrt(s): a factor of e in about 25 s
  Eigen::Vector3d q_prior{1e-3, 1e-3, 1e-3};
  double log_q_prior_sd = 3.0;   // on the first block: weak (a factor of 20)
  double segment_weight = 0.25;  // w above: spacing / segment length
  int max_iterations = 500;

  bool IsValid(std::string* error) const;
};

struct NoiseLikelihoodResult {
  std::vector<Eigen::Vector3d> q;  // per block
  bool ok = false;
  std::string message;  // the minimizer's, or why nothing was fitted
  int iterations = 0;
};

// One segment's negative log-likelihood (r' S^-1 r + log det S) / 2 and, when `gradient` is not
// null, its gradient with respect to q (added to *gradient).
double SegmentNoiseNegativeLogLikelihood(const NoiseLikelihoodSegment& segment,
                                         const Eigen::Vector3d& q, Eigen::Vector3d* gradient);

// The objective above on log q (blocks x 3, block-major) and its gradient; for the tests.
double NoiseObjective(const std::vector<NoiseLikelihoodSegment>& segments, int blocks,
                      const NoiseLikelihoodOptions& options, const double* log_q, double* gradient);

// q per block, starting from q_start (per block, or empty: the prior everywhere). Segments whose
// S is not positive definite at some step make the minimizer step back (never an abort).
NoiseLikelihoodResult FitNoiseByLikelihood(const std::vector<NoiseLikelihoodSegment>& segments,
                                           int blocks, const NoiseLikelihoodOptions& options,
                                           const std::vector<Eigen::Vector3d>& q_start = {});

}  // namespace slipgraph
