// Jet-safe smooth replacements for the kinks of the Ward & Iagnemma force laws.
//
// The force laws contain sign(v) (1 - exp(-A |v|)). Written literally, a ceres::Jet evaluated at
// exactly v = 0 gets derivative 0 (sign(0) = 0 and 1 - exp(0) = 0 kill both product-rule terms),
// while the true derivative there is A. SignedSaturation rewrites the term as
//   A v phi(A |v|),   phi(x) = (1 - exp(-x)) / x,   phi(0) = 1,
// which is the same function, analytic in v, with a Taylor branch for phi near x = 0 (as Sophus
// switches to a Taylor series near zero rotation) so that the value and every derivative stay
// finite and exact at v = 0.
#pragma once

#include <cmath>

namespace slipgraph {

// phi(x) = (1 - exp(-x)) / x for x >= 0, with phi(0) = 1.
template <typename T>
inline T OneMinusExpOverX(const T& x) {
  using std::expm1;
  // Below 1e-3 the 4-term series error x^4/120 is under 1e-14 relative; above, expm1 is exact to
  // rounding (no cancellation in 1 - exp(-x)).
  if (x < 1e-3) return T(1.0) - x / 2.0 + x * x / 6.0 - x * x * x / 24.0;
  return -expm1(-x) / x;
}

// sign(v) (1 - exp(-rate |v|)), smooth at v = 0 with slope `rate` there. rate > 0 (1/units of v).
template <typename T>
inline T SignedSaturation(const T& v, double rate) {
  using std::abs;
  return rate * v * OneMinusExpOverX(T(rate * abs(v)));
}

}  // namespace slipgraph
