// Terrain and sinkage profiles on a uniform grid for Wilcox's estimator as a factor graph: a
// profile is a run of node values v_i at x = (first + i) h, linear in between; a wheel rides on
// the profile averaged over its contact patch (Simpson's rule over 5 points). Templated on the
// position's and the nodes' scalar so the Ceres factors differentiate through both (the
// position moves the interpolation weights). Positions outside the run are clamped to its ends.
#pragma once

#include <algorithm>
#include <cmath>

#include "factors/smooth_math.h"

namespace slipgraph {
namespace wilcox {

struct GridRun {
  int first = 0;  // index of the run's first node in the whole grid
  int count = 0;  // nodes in the run
  double spacing_m = 0.01;
};

// Linear interpolation of the run's nodes (node i of the run: nodes[i][0]) at x.
template <typename T>
inline T ProfileAt(const GridRun& run, T const* const* nodes, const T& x) {
  T u = x / run.spacing_m - static_cast<double>(run.first);
  if (u < T(0.0)) u = T(0.0);
  if (u > T(static_cast<double>(run.count - 1))) u = T(static_cast<double>(run.count - 1));
  const int i = std::min(static_cast<int>(std::floor(ScalarPart(u))), run.count - 2);
  const T f = u - static_cast<double>(i);
  return (1.0 - f) * nodes[i][0] + f * nodes[i + 1][0];
}

// The mean over [x - L/2, x + L/2] (Simpson's rule, 5 points).
template <typename T>
inline T WheelProfileAt(const GridRun& run, T const* const* nodes, const T& x, double patch_m) {
  if (patch_m <= 0.0) return ProfileAt(run, nodes, x);
  const double h = 0.25 * patch_m;
  return (ProfileAt(run, nodes, x - 2.0 * h) + 4.0 * ProfileAt(run, nodes, x - h) +
          2.0 * ProfileAt(run, nodes, x) + 4.0 * ProfileAt(run, nodes, x + h) +
          ProfileAt(run, nodes, x + 2.0 * h)) /
         12.0;
}

// The run of nodes covering [x_lo - margin, x_hi + margin] on a grid of `total` nodes.
inline GridRun RunCovering(double x_lo, double x_hi, double margin_m, double spacing_m, int total) {
  GridRun run;
  run.spacing_m = spacing_m;
  run.first = std::clamp(static_cast<int>(std::floor((x_lo - margin_m) / spacing_m)), 0, total - 2);
  const int last = std::clamp(static_cast<int>(std::ceil((x_hi + margin_m) / spacing_m)),
                              run.first + 1, total - 1);
  run.count = last - run.first + 1;
  return run;
}

}  // namespace wilcox
}  // namespace slipgraph
