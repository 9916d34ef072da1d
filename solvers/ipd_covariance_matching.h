// Innovation-based covariance matching for the IPD predictions' reported covariance (as in
// Mehra's and Myers & Tapley's adaptive filters): each 2 s prediction's covariance, per axis
// (along, cross, heading), is scaled by the recent mean of the squared errors over the predicted
// variances of the predictions whose end poses have been measured, when that mean exceeds 1.
//
// Why: the calibrated Q describes the stochastic slip on a terrain; after a terrain change the
// error is the model's (alpha is the old terrain's) for tens of seconds, and the predictions were
// 2-7 times over-confident there (heading within 20 s of a boundary: predicted / sample variance
// 0.14; docs/ipd.md). Only what is reported changes: the estimates of alpha and Q do not.
//
// Causal: a prediction's error enters the mean only once its segment has ended (its end pose is
// measured) before the prediction being scaled starts. Each normalized squared error is clipped
// at the chi-square (1 dof) 99.9 % point, so one wild pose cannot scale the next ten seconds.
// Inflate only: the calibrated Q is already fitted to these residuals, so the scale does not go
// below 1. Measured on ipd35 seeds 1-3 after the first minute (predicted / sample variance,
// along / cross / heading): EKF 0.85-0.88 / 0.81-0.84 / 0.54-0.62 -> 1.07-1.12 / 1.04-1.07 /
// 0.83-0.92 with a memory of 20 predictions (10 s); 10 and 40 gave 0.87-0.97 and 0.80-0.90 on
// heading; letting the scale fall below 1 left seed 1's heading at 0.79.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <deque>

#include "solvers/ipd_calibration.h"

namespace slipgraph {

class IpdCovarianceMatching {
 public:
  // memory_segments: the mean's memory (an exponential one), in predictions; 0: off.
  explicit IpdCovarianceMatching(double memory_segments, double clip = 10.83)
      : memory_(memory_segments), clip_(clip) {}

  // Scales e's predicted_covariance (and remembers e, whose segment ends at t_end).
  void Apply(double t_end, PredictionError* e) {
    if (!(memory_ > 0.0)) return;
    while (!pending_.empty() && pending_.front().t_end <= e->t_start + 1e-9) {
      const Pending& p = pending_.front();
      for (int a = 0; a < 3; ++a) {
        if (!(p.variance[a] > 0.0)) continue;
        const double normalized = std::min(clip_, p.error[a] * p.error[a] / p.variance[a]);
        mean_[a] += (normalized - mean_[a]) / memory_;
        scale_[a] = std::sqrt(std::max(1.0, mean_[a]));
      }
      pending_.pop_front();
    }
    pending_.push_back({t_end, Eigen::Vector3d(e->along_m, e->cross_m, e->heading_rad),
                        e->predicted_covariance.diagonal()});
    e->predicted_covariance = scale_.asDiagonal() * e->predicted_covariance * scale_.asDiagonal();
  }

  // The current scale of each axis' sd (1: the predictions as calibrated).
  const Eigen::Vector3d& scale() const { return scale_; }

 private:
  struct Pending {
    double t_end;
    Eigen::Vector3d error, variance;  // the prediction's error and unscaled variances
  };
  double memory_, clip_;
  Eigen::Vector3d mean_ = Eigen::Vector3d::Ones(), scale_ = Eigen::Vector3d::Ones();
  std::deque<Pending> pending_;
};

}  // namespace slipgraph
