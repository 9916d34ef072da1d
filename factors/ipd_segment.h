// Integrated Perturbative Dynamics over a path segment (Rogers-Marcovitz, Seegmiller & Kelly):
// the pose predicted from odometry and the measured roll/pitch history with the slip model
// u_s = C alpha (eq. 11), in the frame of the segment's start pose (so it compares with the
// measured relative pose z = rho_{k-1}^-1 (+) rho_k of eq. 12), and the covariance of that
// prediction's error from eq. (15): the end poses' measurement noise through Phi and the
// input noise Q through Gamma = Phi B (eqs. 8-9).
//
// Templated on the slip parameters' scalar so the identification EKF (Jacobian d h / d alpha)
// and the Ceres segment factor share one integration.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "factors/ipd_kinematics.h"

namespace slipgraph {
namespace ipd {

// One odometry step of a segment: nominal forward speed and yaw rate from the encoders, and the
// attitude (REP-103 roll, pitch) at the step; dt to the next step.
struct OdometryStep {
  double dt_s;
  double v_x_mps;
  double v_yaw_radps;
  double roll_rad;
  double pitch_rad;
};

// The end pose (x, y, yaw) relative to the start, Euler integration of rho' = B (u_n + C alpha).
template <typename T>
inline void PredictSegment(const std::vector<OdometryStep>& steps, const T* alpha,
                           double gravity_mps2, T* pose) {
  pose[0] = T(0.0);
  pose[1] = T(0.0);
  pose[2] = T(0.0);
  for (const OdometryStep& s : steps) {
    double g_x, g_y;
    GravityInBody(s.roll_rad, s.pitch_rad, gravity_mps2, &g_x, &g_y);
    T u_s[3];
    SlipVelocities(T(s.v_x_mps), T(s.v_yaw_radps), T(g_x), T(g_y), alpha, u_s);
    const T u[3] = {s.v_x_mps + u_s[0], u_s[1], s.v_yaw_radps + u_s[2]};
    T rho_dot[3];
    PoseRate(T(s.roll_rad), T(s.pitch_rad), pose[2], u, rho_dot);
    for (int i = 0; i < 3; ++i) pose[i] += rho_dot[i] * s.dt_s;
  }
}

// Covariance of the predicted end pose's error, eq. (15), split so the input noise can be
// calibrated (eqs. 18-21): R = measurement + sum_i q_i input[i], where
// measurement = Phi(t, t0) Sigma_start Phi' + Sigma_end and input[i] = integral of
// gamma_i gamma_i' dtau (gamma_i the i-th column of Gamma = Phi B), along the trajectory
// predicted with alpha. q_i: the diagonal of Q, the white-noise densities of (V_x, V_y, V_yaw).
struct PredictionCovarianceTerms {
  Eigen::Matrix3d measurement = Eigen::Matrix3d::Zero();
  std::array<Eigen::Matrix3d, 3> input{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
                                       Eigen::Matrix3d::Zero()};
  Eigen::Matrix3d Total(const Eigen::Vector3d& q) const {
    return measurement + q[0] * input[0] + q[1] * input[1] + q[2] * input[2];
  }
};

inline PredictionCovarianceTerms PredictionCovariance(const std::vector<OdometryStep>& steps,
                                                      const double* alpha, double gravity_mps2,
                                                      const Eigen::Matrix3d& sigma_start,
                                                      const Eigen::Matrix3d& sigma_end) {
  std::vector<Eigen::Vector3d> path;
  path.reserve(steps.size() + 1);
  double pose[3] = {0.0, 0.0, 0.0};
  path.emplace_back(0.0, 0.0, 0.0);
  for (const OdometryStep& s : steps) {
    double g_x, g_y;
    GravityInBody(s.roll_rad, s.pitch_rad, gravity_mps2, &g_x, &g_y);
    double u_s[3];
    SlipVelocities(s.v_x_mps, s.v_yaw_radps, g_x, g_y, alpha, u_s);
    const double u[3] = {s.v_x_mps + u_s[0], u_s[1], s.v_yaw_radps + u_s[2]};
    double rho_dot[3];
    PoseRate(s.roll_rad, s.pitch_rad, pose[2], u, rho_dot);
    for (int i = 0; i < 3; ++i) pose[i] += rho_dot[i] * s.dt_s;
    path.emplace_back(pose[0], pose[1], pose[2]);
  }
  const Eigen::Vector3d end = path.back();
  const auto Phi = [&](const Eigen::Vector3d& from) {
    Eigen::Matrix3d phi = Eigen::Matrix3d::Identity();
    phi(0, 2) = -(end[1] - from[1]);
    phi(1, 2) = end[0] - from[0];
    return phi;
  };
  PredictionCovarianceTerms out;
  for (auto& m : out.input) m.setZero();
  out.measurement = Phi(path.front()) * sigma_start * Phi(path.front()).transpose() + sigma_end;
  for (size_t k = 0; k < steps.size(); ++k) {
    const OdometryStep& s = steps[k];
    const double cy = std::cos(path[k][2]), sy = std::sin(path[k][2]);
    const double cb = std::cos(s.pitch_rad), sb = std::sin(s.pitch_rad);
    const double cg = std::cos(s.roll_rad), sg = std::sin(s.roll_rad);
    Eigen::Matrix3d B;
    B << cy * cb, cy * sb * sg - sy * cg, 0.0,  //
        sy * cb, sy * sb * sg + cy * cg, 0.0,   //
        0.0, 0.0, cg / cb;
    const Eigen::Matrix3d gamma = Phi(path[k]) * B;
    for (int i = 0; i < 3; ++i) {
      out.input[i] += gamma.col(i) * gamma.col(i).transpose() * s.dt_s;
    }
  }
  return out;
}

// The measured relative pose rho_start^-1 (+) rho_end (eq. 12), yaw wrapped to (-pi, pi].
inline Eigen::Vector3d RelativePose(double x0, double y0, double yaw0, double x1, double y1,
                                    double yaw1) {
  const double c = std::cos(yaw0), s = std::sin(yaw0);
  const double dx = x1 - x0, dy = y1 - y0;
  return {c * dx + s * dy, -s * dx + c * dy, std::remainder(yaw1 - yaw0, 2.0 * M_PI)};
}

}  // namespace ipd
}  // namespace slipgraph
