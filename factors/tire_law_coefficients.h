// The tire and rolling laws' coefficients as unknowns, [C1, At, C2, R1, R2] of eqs. (8) and (9),
// and the two sides' rolling-radius errors: what `slipgraph identify` fits
// (solvers/model_identification.h) through the accelerometer factor's law blocks
// (factors/accelerometer_factor.h). A_roll, the static part's smoothing near v = 0, stays the
// model's: the data at walking speeds do not see it. Eq. (8)'s rate At enters through the
// saturation's argument with the model's At as the reference (TractionForceOf in
// factors/traction.h); x' is the state with each side's wheel speed scaled by (1 + e_side).
#pragma once

#include <array>

#include "factors/traction.h"
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

}  // namespace slipgraph
