// Measurement model of Ward & Iagnemma, eq. (11):
//
//   z = [ a_x_imu, yaw_rate_imu, v_x_gps, w_l_enc, w_r_enc ]
//   h(x) = [ f_tire + c_ax + b_ax + a_dist,  yaw_rate + c_gz + b_gz,  v_bx,  w_l,  w_r ]
//
// a_x_imu is the accelerometer's specific force along body x (gravity included, m/s^2): on a
// slope it reads v_bx' + g sin(phi) = f_tire + a_dist, which is why gravity does not appear.
// c_ax, c_gz are the constant IMU offsets (EMA of eq. 12 in the EKF, estimated in the smoother).
// v_x_gps is the GNSS velocity projected on body x (m/s).
#pragma once

#include "factors/ward_dynamics.h"
#include "factors/ward_state.h"

namespace slipgraph {
namespace ward {

enum MeasurementIndex : int {
  kZAccelX = 0,
  kZYawRate = 1,
  kZGpsVx = 2,
  kZOmegaLeft = 3,
  kZOmegaRight = 4,
};
constexpr int kMeasurementSize = 5;

// Constant IMU offsets c_ax (m/s^2) and c_gz (rad/s).
template <typename T>
struct ImuOffsets {
  T accel_x_mps2;
  T gyro_z_radps;
};

// forces_out (optional): the tire forces behind the accelerometer row.
template <typename T, typename A>
inline void PredictMeasurements(const T* x, const AttitudeLoads<A>& loads, const ImuOffsets<A>& c,
                                const Params& p, T* z, TireForces<T>* forces_out = nullptr) {
  const TireForces<T> forces = ComputeTireForces(x, loads, p);
  if (forces_out != nullptr) *forces_out = forces;
  z[kZAccelX] = forces.f_tire_mps2 + c.accel_x_mps2 + x[kAccelBias] + x[kAdist];
  z[kZYawRate] = x[kYawRate] + c.gyro_z_radps + x[kGyroBias];
  z[kZGpsVx] = x[kVbx];
  z[kZOmegaLeft] = x[kOmegaLeft];
  z[kZOmegaRight] = x[kOmegaRight];
}

template <typename T, typename A>
inline void PredictMeasurements(const T* x, const Attitude<A>& attitude, const ImuOffsets<A>& c,
                                const Params& p, T* z) {
  PredictMeasurements(x, ComputeAttitudeLoads(attitude, p), c, p, z);
}

}  // namespace ward
}  // namespace slipgraph
