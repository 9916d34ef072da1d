// The accelerometer factor with the tire and rolling laws and the wheels' rolling radii as
// unknowns: the factor `slipgraph identify` fits them with (solvers/model_identification.h).
//
//   r = (a_x - (f_tire(x'; law) + c_ax + b_ax + a_dist)) / sd_a
//
// law = [C1, At, C2, R1, R2] of eqs. (8) and (9) (A_roll, the static part's smoothing near
// v = 0, stays the model's: the data at walking speeds do not see it), and x' the state with
// each side's wheel speed scaled by (1 + e_side), e_side that side's rolling-radius error (as
// the wheel_radius_error effect, per side). Eq. (8)'s rate At enters through the saturation's
// argument with the model's At as the reference (TractionForceOf in factors/traction.h).
//
// Parameter blocks: x_k (7), IMU offsets [c_ax, c_gz] (2), law (5), radius errors [e_l, e_r]
// (2). At the model's law and zero radius errors it is AccelerometerFactor exactly
// (tests/law_accelerometer_factor_test.cpp).
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <array>

#include "factors/imu_factor.h"
#include "factors/ward_dynamics.h"

namespace slipgraph {

enum LawCoefficient { kLawC1 = 0, kLawAt, kLawC2, kLawR1, kLawR2, kLawCoefficientCount };

inline const std::array<const char*, kLawCoefficientCount>& LawCoefficientNames() {
  static const std::array<const char*, kLawCoefficientCount> kNames = {
      "tire.C1", "tire.At", "tire.C2", "rolling.R1", "rolling.R2"};
  return kNames;
}

inline std::array<double, kLawCoefficientCount> LawCoefficients(const TireParams& tire,
                                                                const RollingParams& rolling) {
  return {tire.C1, tire.At, tire.C2, rolling.R1, rolling.R2};
}

inline void SetLawCoefficients(const std::array<double, kLawCoefficientCount>& law,
                               TireParams* tire, RollingParams* rolling) {
  tire->C1 = law[kLawC1];
  tire->At = law[kLawAt];
  tire->C2 = law[kLawC2];
  rolling->R1 = law[kLawR1];
  rolling->R2 = law[kLawR2];
}

// f_tire with the law and the radius errors as parameters (T: every block's scalar).
template <typename T, typename A>
inline ward::TireForces<T> TireForcesWithLaw(const T* x, const ward::AttitudeLoads<A>& loads,
                                             const ward::Params& p, const T* law,
                                             const T* radius_error) {
  T state[ward::kStateSize];
  for (int i = 0; i < ward::kStateSize; ++i) state[i] = x[i];
  state[ward::kOmegaLeft] *= T(1.0) + radius_error[0];
  state[ward::kOmegaRight] *= T(1.0) + radius_error[1];
  const double at_reference = p.tire.At;
  const double a_roll = p.rolling.A_roll;
  return ward::ComputeTireForcesWith(
      state, loads, p,
      [&](const A& n, const T& v_rel) {
        return TractionForceOf(n, v_rel, law[kLawC1], law[kLawAt], law[kLawC2], at_reference);
      },
      [&](const T& v_fwd) {
        return RollingResistancePerNewtonOf(v_fwd, law[kLawR1], a_roll, law[kLawR2]);
      });
}

struct LawAccelerometerFactor {
  LawAccelerometerFactor(const ward::Params& params, const ward::Attitude<double>& attitude,
                         double accel_x_mps2, double sd_mps2)
      : reading_(params, attitude, accel_x_mps2, sd_mps2) {}

  template <typename T>
  bool operator()(const T* x, const T* offsets, const T* law, const T* radius_error,
                  T* residual) const {
    const ward::TireForces<T> forces =
        TireForcesWithLaw(x, reading_.loads, reading_.params, law, radius_error);
    residual[0] = reading_.Residual(forces.f_tire_mps2, x, offsets);
    return true;
  }

  static ceres::CostFunction* Create(const ward::Params& params,
                                     const ward::Attitude<double>& attitude, double accel_x_mps2,
                                     double sd_mps2) {
    return new ceres::AutoDiffCostFunction<LawAccelerometerFactor, 1, ward::kStateSize, 2,
                                           kLawCoefficientCount, 2>(
        new LawAccelerometerFactor(params, attitude, accel_x_mps2, sd_mps2));
  }

 private:
  AccelerometerReading reading_;
};

}  // namespace slipgraph
