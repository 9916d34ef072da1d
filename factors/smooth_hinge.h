// Smooth one-sided penalties for the soft priors (weak constraints in the smoother): no
// if-statement on the state, finite derivatives everywhere.
//
//   SmoothHinge(u) = (u + sqrt(u^2 + eps^2)) / 2   ~ max(u, 0), exact to eps/2 at u = 0
//   SmoothAbs(u)   = sqrt(u^2 + eps^2) - eps        ~ |u|
#pragma once

#include <cmath>

namespace slipgraph {

template <typename T>
inline T SmoothHinge(const T& u, double eps) {
  using std::sqrt;
  return 0.5 * (u + sqrt(u * u + eps * eps));
}

template <typename T>
inline T SmoothAbsolute(const T& u, double eps) {
  using std::sqrt;
  return sqrt(u * u + eps * eps) - eps;
}

}  // namespace slipgraph
