// IPD slip-model identification as a Ceres factor graph (issue 7's "same as Ceres residual
// blocks"), beside the paper's EKF (solvers/ipd_calibration.h).
#pragma once

#include "solvers/ipd_calibration.h"
#include "solvers/ipd_noise_likelihood.h"

namespace slipgraph {

// The Ceres form (factors/ipd_segment_factor.h): alpha as one 13-block per `block_s` of driving
// (`window_block_s` in the window), consecutive blocks tied by the random walk, one pose-residual
// factor per segment on the block of its midpoint. "window" is online: after each block it solves
// the blocks of the last `window_s` with at most `max_iterations` and marginalizes older blocks
// into a prior
// (problems/marginalization); a segment is predicted with the newest solved block. "batch"
// solves the whole log at once and predicts each segment with its own block (post-processing,
// not causal). Q: in the window from StochasticCalibrator (the paper's online method); in the batch
// by maximum likelihood per block (q_by_likelihood), starting from the EKF's.
struct IpdGraphOptions {
  // The batch's alpha blocks (5 s: 0.0611 m on ipd35 seed 1, 0.0621 with 0.5 s blocks).
  double block_s = 5.0;
  // The window's blocks: it solves after each, so 0.5 s (a segment's spacing) keeps alpha as
  // fresh as the EKF's. Measured on ipd35 seeds 1-3 (mean position error; EKF 0.0709 / 0.0698 /
  // 0.0695 m): 5 s blocks in a 60 s window, 10 iterations 0.0718 / 0.0710 / 0.0726; 1 s blocks
  // 0.0710 / 0.0694 / 0.0696; 0.5 s blocks in a 10 s window, 3 iterations 0.0703 / 0.0692 /
  // 0.0690. The window's length barely matters once the marginal prior carries the rest (30 s and
  // 60 s gave the same figures; 5 s 0.0703 / 0.0692 / 0.0692); 1-3 iterations the same, 10 worse
  // on seed 1 (0.0709).
  double window_block_s = 0.5;
  double window_s = 10.0;
  int max_iterations = 3;
  // The walk between alpha blocks is Gaussian up to this norm of the whitened 13-vector and
  // Huber beyond: a terrain change is a jump, not a drift. 5.26 = sqrt of the 99 % point of
  // chi-square with 13 dof (1 % of ordinary steps are down-weighted). 0: Gaussian throughout.
  double walk_huber_sd = 5.26;
  // As the EKF re-admits a second failing segment in a row (IpdOptions::readmit_after): when
  // that many segments in a row fail the 99.99 % gate at the newest alpha, the walk into their
  // block is replaced by one of this sd (a jump: the terrain changed). 0: never.
  double jump_sd = 0.05;
  // The batch's Q: by maximum likelihood per block from the residuals its alpha leaves
  // (solvers/ipd_noise_likelihood.h), alpha solved again with it, this many rounds; false: the
  // online EKF's final Q for the whole log. q_likelihood's block_s, segment_weight and q_prior
  // are set from the batch (block_s, spacing / segment length, the EKF's final Q).
  bool q_by_likelihood = true;
  int q_likelihood_rounds = 2;
  NoiseLikelihoodOptions q_likelihood;
  // Each field in its range; the first that is not is named in *error.
  bool IsValid(std::string* error) const;
};
IpdCalibrationResult CalibrateIpdWindow(const DriveLog& log, const IpdOptions& options = {},
                                        const IpdGraphOptions& graph = {});
IpdCalibrationResult CalibrateIpdBatch(const DriveLog& log, const IpdOptions& options = {},
                                       const IpdGraphOptions& graph = {});

}  // namespace slipgraph
