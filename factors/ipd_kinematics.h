// Velocity kinematics and slip model of Rogers-Marcovitz, Seegmiller & Kelly (IPD).
//
// Pose rho = (x, y, yaw) in the world frame, body-frame inputs u = (V_x, V_y, V_yaw) (forward,
// left, counter-clockwise yaw rate), roll gamma and pitch beta of the body (REP-103 angles):
//
//   rho' = B(gamma, beta, yaw) u                                                   eqs. (1)-(2)
//   B = [ c(yaw)c(beta)   c(yaw)s(beta)s(gamma) - s(yaw)c(gamma)   0
//         s(yaw)c(beta)   s(yaw)s(beta)s(gamma) + c(yaw)c(gamma)   0
//         0               0                                        c(gamma)/c(beta) ]
//
// Slip velocities u_s = C(u_n, g) alpha, eqs. (16)-(17), with 13 parameters:
//   V_s,x   = [V_x, |V_yaw|, V_x |V_yaw|, g_x]     . alpha[0..3]
//   V_s,y   = [V_x, V_yaw,   V_x V_yaw,   g_y]     . alpha[4..7]
//   V_s,yaw = [V_x, V_yaw,   V_x V_yaw,   g_x, g_y] . alpha[8..12]
// where u_n = (V_x, 0, V_yaw) is the nominal (odometry) velocity and (g_x, g_y) the gravity
// vector's components in body axes (m/s^2; g_x > 0 when the nose points downhill).
// |V_yaw| is written as a smooth absolute value so the parameter Jacobian is exact and the
// input Jacobian finite at V_yaw = 0.
#pragma once

#include <cmath>

namespace slipgraph {
namespace ipd {

constexpr int kAlphaSize = 13;
constexpr int kPoseSize = 3;      // x, y, yaw
constexpr int kVelocitySize = 3;  // V_x, V_y, V_yaw

// Smoothing width of |V_yaw| (rad/s): sqrt(w^2 + eps^2) - eps, exact to 1e-4 rad/s.
constexpr double kAbsSmoothingRadps = 1e-4;

template <typename T>
inline T SmoothAbs(const T& value, double eps) {
  using std::sqrt;
  return sqrt(value * value + eps * eps) - eps;
}

// Gravity in body axes from REP-103 roll and pitch: g_body = R^T (0, 0, -g).
template <typename T>
inline void GravityInBody(const T& roll_rad, const T& pitch_rad, double g, T* g_x, T* g_y) {
  using std::cos;
  using std::sin;
  *g_x = g * sin(pitch_rad);
  *g_y = -g * sin(roll_rad) * cos(pitch_rad);
}

// u_s = C(u_n, g) alpha.
template <typename T, typename P>
inline void SlipVelocities(const T& v_x, const T& v_yaw, const T& g_x, const T& g_y, const P* alpha,
                           T* u_s) {
  const T abs_yaw = SmoothAbs(v_yaw, kAbsSmoothingRadps);
  u_s[0] = alpha[0] * v_x + alpha[1] * abs_yaw + alpha[2] * v_x * abs_yaw + alpha[3] * g_x;
  u_s[1] = alpha[4] * v_x + alpha[5] * v_yaw + alpha[6] * v_x * v_yaw + alpha[7] * g_y;
  u_s[2] = alpha[8] * v_x + alpha[9] * v_yaw + alpha[10] * v_x * v_yaw + alpha[11] * g_x +
           alpha[12] * g_y;
}

// rho' = B(roll, pitch, yaw) u.
template <typename T>
inline void PoseRate(const T& roll_rad, const T& pitch_rad, const T& yaw_rad, const T* u,
                     T* rho_dot) {
  using std::cos;
  using std::sin;
  const T cy = cos(yaw_rad), sy = sin(yaw_rad);
  const T cb = cos(pitch_rad), sb = sin(pitch_rad);
  const T cg = cos(roll_rad), sg = sin(roll_rad);
  rho_dot[0] = cy * cb * u[0] + (cy * sb * sg - sy * cg) * u[1];
  rho_dot[1] = sy * cb * u[0] + (sy * sb * sg + cy * cg) * u[1];
  rho_dot[2] = cg / cb * u[2];
}

}  // namespace ipd
}  // namespace slipgraph
