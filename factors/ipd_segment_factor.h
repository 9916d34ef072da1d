// IPD pose-residual factor of one path segment (Rogers-Marcovitz et al. eqs. 11-13, 15):
//
//   r = L^-1 (z - h(alpha)),   L L' = R_sys,
//
// z the measured relative pose of the segment's end (eq. 12), h the prediction from odometry,
// attitude and the slip parameters (factors/ipd_segment.h), heading wrapped. R_sys is fixed when
// the factor is built (from the alpha and Q known then). Parameter block: alpha (13).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "factors/ipd_segment.h"
#include "factors/smooth_math.h"

namespace slipgraph {
struct IpdSegmentFactor {
  IpdSegmentFactor(std::vector<ipd::OdometryStep> steps, const Eigen::Vector3d& measured,
                   const Eigen::Matrix3d& covariance, double gravity_mps2)
      : steps_(std::move(steps)), measured_(measured), gravity_mps2_(gravity_mps2) {
    sqrt_information_ = Eigen::Matrix3d(covariance.llt().matrixL()).inverse();
  }

  template <typename T>
  bool operator()(const T* alpha, T* residual) const {
    T predicted[3];
    ipd::PredictSegment(steps_, alpha, gravity_mps2_, predicted);
    T error[3] = {measured_[0] - predicted[0], measured_[1] - predicted[1],
                  measured_[2] - predicted[2]};
    // Wrap the heading error by the value's whole turns (a constant shift, derivative kept).
    error[2] -= 2.0 * M_PI * std::round(ScalarPart(error[2]) / (2.0 * M_PI));
    for (int r = 0; r < 3; ++r) {
      residual[r] = T(0.0);
      for (int c = 0; c <= r; ++c) residual[r] += sqrt_information_(r, c) * error[c];
    }
    return true;
  }

  static ceres::CostFunction* Create(std::vector<ipd::OdometryStep> steps,
                                     const Eigen::Vector3d& measured,
                                     const Eigen::Matrix3d& covariance, double gravity_mps2) {
    return new ceres::AutoDiffCostFunction<IpdSegmentFactor, 3, ipd::kAlphaSize>(
        new IpdSegmentFactor(std::move(steps), measured, covariance, gravity_mps2));
  }

 private:
  std::vector<ipd::OdometryStep> steps_;
  Eigen::Vector3d measured_;
  double gravity_mps2_;
  Eigen::Matrix3d sqrt_information_;  // lower triangular
};

}  // namespace slipgraph
