// Static normal forces on the tires, Ward & Iagnemma eqs. (3)-(5), longitudinal acceleration
// neglected (slow robots).
//
// Diff-drive with rear castors on a pivot (equal rear loads), W = m g, phi = pitch uphill
// positive, theta = roll right-side-down positive (see frames.h), a/b = CG to front/rear axle,
// c = track width, h = CG height:
//   N_front_left  = W/2 cos(phi) ( (b cos(theta) - h tan(phi)) / (a+b) - 2h/c sin(theta) )  (3)
//   N_front_right = W/2 cos(phi) ( (b cos(theta) - h tan(phi)) / (a+b) + 2h/c sin(theta) )  (4)
//   N_rear_each   = W / (2(a+b)) ( h sin(phi) + a cos(phi) cos(theta) )                     (5)
// Ward's wheel 1 is the left front wheel (the one unloaded by positive roll).
//
// All-wheel-drive vehicles (skid steer, rocker-bogie) need only each side's total, the sum of
// (3)+(5) or (4)+(5):
//   N_left/right = W cos(phi) ( cos(theta) / 2 -/+ h/c sin(theta) )
// (rocker-bogie: the bogies share a side's load about equally among its three wheels).
#pragma once

#include <cmath>

namespace slipgraph {

template <typename T>
struct DiffDriveNormalForces {
  T front_left_n;
  T front_right_n;
  T rear_each_n;  // N3 = N4
};

template <typename T>
inline DiffDriveNormalForces<T> DiffDriveCastorNormalForcesN(
    double weight_n, const T& roll_ward_rad, const T& pitch_uphill_rad, double cg_to_front_m,
    double cg_to_rear_m, double track_width_m, double cg_height_m) {
  using std::cos;
  using std::sin;
  using std::tan;
  const double a = cg_to_front_m, b = cg_to_rear_m, c = track_width_m, h = cg_height_m;
  const T front_common = (b * cos(roll_ward_rad) - h * tan(pitch_uphill_rad)) / (a + b);
  const T roll_transfer = 2.0 * h / c * sin(roll_ward_rad);
  const T half_weight_cos_pitch = 0.5 * weight_n * cos(pitch_uphill_rad);
  return {half_weight_cos_pitch * (front_common - roll_transfer),
          half_weight_cos_pitch * (front_common + roll_transfer),
          weight_n / (2.0 * (a + b)) *
              (h * sin(pitch_uphill_rad) + a * cos(pitch_uphill_rad) * cos(roll_ward_rad))};
}

template <typename T>
struct SideNormalForces {
  T left_n;
  T right_n;
};

template <typename T>
inline SideNormalForces<T> SideTotalNormalForcesN(double weight_n, const T& roll_ward_rad,
                                                  const T& pitch_uphill_rad, double track_width_m,
                                                  double cg_height_m) {
  using std::cos;
  using std::sin;
  const T base = weight_n * cos(pitch_uphill_rad);
  const T half_cos_roll = 0.5 * cos(roll_ward_rad);
  const T transfer = cg_height_m / track_width_m * sin(roll_ward_rad);
  return {base * (half_cos_roll - transfer), base * (half_cos_roll + transfer)};
}

}  // namespace slipgraph
