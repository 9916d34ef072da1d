// Jet-safe smooth replacements for the kinks of the Ward & Iagnemma force laws.
//
// The force laws contain sign(v) (1 - exp(-A |v|)). Written literally, a ceres::Jet evaluated at
// exactly v = 0 gets derivative 0 (sign(0) = 0 and 1 - exp(0) = 0 kill both product-rule terms),
// while the true derivative there is A. SignedSaturation computes the same function as
//   A v phi(A |v|),   phi(x) = (1 - exp(-x)) / x,   phi(0) = 1,
// analytic in v, with a Taylor branch for phi near x = 0 (as Sophus switches to a Taylor series
// near zero rotation), and gives Jets the exact derivative A exp(-A |v|) directly (one exp, no
// chain of Jet operations: it sits in the filter's inner loop). The double and the Jet versions
// compute the value the same way, so that a double pass and a Jet pass agree to the bit.
#pragma once

#include <ceres/jet.h>

#include <cmath>

namespace slipgraph {

// phi(x) = (1 - exp(-x)) / x for x >= 0, with phi(0) = 1.
template <typename T>
inline T OneMinusExpOverX(const T& x) {
  using std::exp;
  // Below 1e-3 the 4-term series error x^4/120 is under 1e-14 relative; above, 1 - exp(-x) loses
  // at most 1e-13 relative to cancellation (exp costs about half of expm1, and the tire laws
  // evaluate this four times per tire-force evaluation, in the EKF's inner loop).
  if (x < 1e-3) return T(1.0) - x / 2.0 + x * x / 6.0 - x * x * x / 24.0;
  return (T(1.0) - exp(-x)) / x;
}

// sign(v) (1 - exp(-rate |v|)), smooth at v = 0 with slope `rate` there. rate > 0 (1/units of v).
inline double SignedSaturation(double v, double rate) {
  return rate * v * OneMinusExpOverX(rate * std::abs(v));
}

// The Jet version: value as above, derivative rate exp(-rate |v|) times v's derivative.
template <typename S, int N>
inline ceres::Jet<S, N> SignedSaturation(const ceres::Jet<S, N>& v, double rate) {
  using std::exp;
  const S x = rate * std::abs(v.a);
  // One exp serves both parts, the value as OneMinusExpOverX computes it.
  const S exp_minus_x = exp(-x);
  const S value = x < 1e-3 ? OneMinusExpOverX(x) : (1.0 - exp_minus_x) / x;
  return ceres::Jet<S, N>(rate * v.a * value, v.v * (rate * exp_minus_x));
}

// The value part of a scalar, for the few places that branch or round on it (a grid index, a
// whole turn of heading) while the derivative passes through untouched.
inline double ScalarPart(double v) { return v; }
template <typename S, int N>
inline double ScalarPart(const ceres::Jet<S, N>& v) {
  return v.a;
}

}  // namespace slipgraph
