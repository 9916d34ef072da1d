// The variance of the tire law's traction acceleration at a state, from the model's
// TireLawUncertainty (model/model_config.h):
//
//   var = (relative_sd |traction|)^2 + sum_sides (d traction/d v_rel (slip_relative_sd |v_rel|
//         + slip_floor))^2 + floor^2
//
// Shared by the EKF's accelerometer update and the smoother's accelerometer factor, so both
// weigh the law the same way.
#pragma once

#include <ceres/jet.h>

#include <algorithm>
#include <cmath>

#include "factors/ward_dynamics.h"
#include "model/model_config.h"

namespace slipgraph {

// From tire forces already evaluated on Jets whose slots left_slot and right_slot are the wheel
// speeds (the EKF's accelerometer row has them from its 7-wide Jet): no second evaluation.
template <typename JetT>
inline double TireLawVarianceOf(const ward::TireForces<JetT>& f, int left_slot, int right_slot,
                                const ward::Params& params, const TireLawUncertainty& u) {
  // r d/d v_rel = d/d w.
  const double traction = std::abs(f.traction_left_n.a + f.traction_right_n.a) / params.mass_kg;
  const double slope_left =
      std::abs(f.traction_left_n.v[left_slot]) / params.mass_kg / params.wheel_radius_m;
  const double slope_right =
      std::abs(f.traction_right_n.v[right_slot]) / params.mass_kg / params.wheel_radius_m;
  const double slip_left =
      slope_left * (u.slip_relative_sd * std::abs(f.v_rel_left_mps.a) + u.slip_floor_mps);
  const double slip_right =
      slope_right * (u.slip_relative_sd * std::abs(f.v_rel_right_mps.a) + u.slip_floor_mps);
  return u.relative_sd * traction * u.relative_sd * traction + slip_left * slip_left +
         slip_right * slip_right + u.floor_mps2 * u.floor_mps2;
}

inline double TireLawVariance(const double* x, const ward::AttitudeLoads<double>& loads,
                              const ward::Params& params, const TireLawUncertainty& u) {
  // Differentiate the traction with respect to the two wheel speeds.
  using Jet2 = ceres::Jet<double, 2>;
  Jet2 state[ward::kStateSize];
  for (int i = 0; i < ward::kStateSize; ++i) state[i] = Jet2(x[i]);
  state[ward::kOmegaLeft] = Jet2(x[ward::kOmegaLeft], 0);
  state[ward::kOmegaRight] = Jet2(x[ward::kOmegaRight], 1);
  return TireLawVarianceOf(ward::ComputeTireForces(state, loads, params), 0, 1, params, u);
}

// The law's variance as the noise of one accelerometer sample of interval sample_interval_s: its
// error persists over correlation_time, so the per-sample variance grows by correlation_time /
// interval (never below the plain variance).
inline double TireLawSampleScale(const TireLawUncertainty& u, double sample_interval_s) {
  return std::max(1.0, u.correlation_time_s / sample_interval_s);
}

inline double TireLawSampleVariance(const double* x, const ward::AttitudeLoads<double>& loads,
                                    const ward::Params& params, const TireLawUncertainty& u,
                                    double sample_interval_s) {
  return TireLawVariance(x, loads, params, u) * TireLawSampleScale(u, sample_interval_s);
}

}  // namespace slipgraph
