// Terrain memory for the IPD slip-model identification: the slip models identified on earlier
// stretches of a drive, recalled when the robot is back on a terrain it has driven before.
//
// Rogers-Marcovitz et al. follow a terrain change by re-identifying the 13 parameters from the
// new terrain's segments, and note that "one could use the parameters calibrated for the same
// vehicle on different terrain as a better initial guess". On a drive that returns to a terrain,
// the best guess is the model that terrain already has: without perception, the segments
// themselves say which one it is. This is multiple-model hypothesis testing on the segments'
// predictive likelihood:
//
// - Store: when a persistent misfit (the EKF's re-admission, a terrain change) ends a model that
//   had been in use for at least `settle_s`, the model (alpha, its covariance P, the calibrated
//   Q) is kept. A model statistically the same as one stored (the alphas' difference inside the
//   chi-square 99 % point of 13 dof under the sum of their covariances) replaces it; the bank
//   holds `capacity` models, the least recently used dropped.
// - Search: for `search_s` after a misfit, every ended segment is scored under each stored model
//   (alpha fixed, P grown by the alpha walk since it was stored, its own Q) and under the
//   current model, before the current model updates on it: log-likelihood
//   -(r' S^-1 r + log det S) / 2 with S = H P H' + R_sys(q).
// - Recall: a stored model is taken when, over the last `window` scored segments (at least two),
//   its log-likelihood beats the current model's by ln(100) (a Bayes factor of 100, "decisive" on
//   Jeffreys' scale) and its own normalized innovations pass the chi-square 99 % point of 3 n
//   dof (it explains the segments, not just better than a bad current model).
//
// A wrong recall costs nothing lasting: the EKF goes on updating the recalled model, its gate
// and re-admission work as before.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <deque>
#include <string>
#include <vector>

#include "factors/ipd_kinematics.h"
#include "solvers/ipd_calibration.h"

namespace slipgraph {

struct IpdSlipModel {
  Eigen::Matrix<double, ipd::kAlphaSize, 1> alpha =
      Eigen::Matrix<double, ipd::kAlphaSize, 1>::Zero();
  Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize> P =
      Eigen::Matrix<double, ipd::kAlphaSize, ipd::kAlphaSize>::Zero();
  Eigen::Vector3d q = Eigen::Vector3d::Zero();
};

// The log-likelihood of a segment's residual under a model, and its normalized innovation.
struct SegmentLikelihood {
  double log_likelihood = 0.0;  // -(nis + log det S) / 2
  double nis = 0.0;
};
// From a residual and the factored covariance S of its prediction (the EKF, the window and
// ScoreSegment all score this way).
SegmentLikelihood Likelihood(const Eigen::Vector3d& residual,
                             const Eigen::LDLT<Eigen::Matrix3d>& S);
SegmentLikelihood ScoreSegment(const IpdSegment& segment, const IpdSlipModel& model,
                               const IpdOptions& options);

class IpdTerrainMemory {
 public:
  explicit IpdTerrainMemory(const IpdOptions& ipd);

  // A persistent misfit at time t: stores `current` when it has been in use since `in_use_since`
  // for settle_s or more, and opens a search.
  void Misfit(const IpdSlipModel& current, double in_use_since, double t);

  // Scores an ended segment (before the current model updates on it), given the current model's
  // log-likelihood of it. Returns true and fills *recalled when a stored model should replace the
  // current one (its P grown by the walk since it was stored).
  bool Score(const IpdSegment& segment, double current_log_likelihood, IpdSlipModel* recalled);

  size_t size() const { return models_.size(); }
  int stored() const { return stored_; }
  int merged() const { return merged_; }
  // The run's note ("terrain memory: ..."), given how many recalls the caller applied; empty
  // when nothing was stored or recalled.
  std::string Describe(long recalled) const;

 private:
  struct Stored {
    IpdSlipModel model;
    double stored_t = 0.0, used_t = 0.0;
    std::deque<SegmentLikelihood> recent;
  };
  IpdOptions ipd_;
  IpdTerrainMemoryOptions options_;
  std::vector<Stored> models_;
  std::deque<double> current_recent_;  // the current model's log-likelihoods
  double search_until_ = -1e300;
  int stored_ = 0, merged_ = 0;
  double same_terrain_;            // chi-square 99 % point, 13 dof
  std::vector<double> nis_bound_;  // chi-square 99 % point of 3 n dof, by n segments

  IpdSlipModel Grown(const Stored& s, double t) const;
  void Store(const IpdSlipModel& model, double t);
  void RestartComparison();
};

}  // namespace slipgraph
