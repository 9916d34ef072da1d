// The LAGR robot of Ward & Iagnemma as physics parameters, shared by the Ward model tests.
#pragma once

#include <Eigen/Core>

#include "factors/ward_state.h"

namespace slipgraph {
namespace testing {

inline ward::Params LagrParams(VehicleType type = VehicleType::kDiffDriveCastor) {
  ward::Params p;
  p.type = type;
  p.mass_kg = 117.0;
  p.yaw_inertia_kgm2 = 15.0;
  p.wheel_radius_m = 0.25;
  p.track_width_m = 0.55;
  p.cg_to_front_m = 0.35;
  p.cg_to_rear_m = 0.55;
  p.cg_height_m = 0.30;
  p.tire = {0.8, 20.0, 0.05};
  p.rolling = {0.03, 20.0, 0.01};
  return p;
}

// A state of the LAGR robot driving at 0.8 m/s with a little slip, a turn and small biases.
inline Eigen::Matrix<double, ward::kStateSize, 1> MovingWardState() {
  Eigen::Matrix<double, ward::kStateSize, 1> x;
  x << 0.8, 0.02, -0.1, 3.4, 3.5, 0.04, 0.001;
  return x;
}

}  // namespace testing
}  // namespace slipgraph
