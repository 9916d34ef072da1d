// Wilcox's measurements as Ceres factors on profile nodes (factors/wilcox_profile.h), one side:
//
//   range:        r = (z - [y(x_k + d) - (ybar(x_k) - s(x_k))]) / sd_range
//   articulation: r = (z - [(ybar - s)(x_k + n A) - (ybar - s)(x_k)]) / sd       (n = 1, 2)
//
// x_k the rear wheel's contact position at cycle k, y the undisturbed terrain (what the ranging
// sensor sees), s the sinkage, ybar the terrain averaged over a wheel's contact patch (what a
// wheel rides on, with s). Parameter blocks: x_k (size 1), then the y node blocks the near and far
// runs touch, then the s node blocks (block_size consecutive nodes each, ascending; Prepare lists
// them). The runs are fixed when the factor is built, with a margin for x_k to move.
//
// The prediction is a weighted sum of profile probes, w * profile(x_k + offset) (ForEachProbe):
// the templated operator() evaluates it (the search, and the reference in the tests), and Create
// returns a cost function with the analytic Jacobian of the same probes (interpolation weights on
// the nodes, the profile's slope on x_k), checked against numeric differentiation in
// tests/wilcox_factors_test.cpp.
//
// Why blocks of nodes and an analytic Jacobian: Ceres' symbolic work on J^T J grows with the
// square of the number of parameter blocks a residual touches, and automatic differentiation with
// the number of node values; with one block per node (50-60 per factor) and dynamic autodiff the
// two were most of a graph run's time.
#pragma once

#include <ceres/cost_function.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "factors/wilcox_profile.h"

namespace slipgraph {

struct WilcoxMeasurementFactor {
  enum Kind { kRange, kArticulation };
  enum Profile { kTerrain, kSinkage };
  Kind kind;
  double offset_m;  // d (range) or n A (articulation)
  double measured_m;
  double sd_m;
  double patch_m;
  wilcox::GridRun y_near, y_far, s_near, s_far;  // s_far.count == 0 for a range factor
  int block_size = 1;                            // nodes per parameter block

  // The node blocks the runs touch, ascending (filled by Prepare).
  std::vector<int> y_blocks = {}, s_blocks = {};

  // Lists the node blocks the runs touch; call after setting the runs and block_size.
  void Prepare() {
    y_blocks = BlocksTouched(y_near, y_far);
    s_blocks = BlocksTouched(s_near, s_far);
  }
  int BlockCount() const { return 1 + static_cast<int>(y_blocks.size() + s_blocks.size()); }

  // The prediction's probes: visit(profile, run, offset from x_k, weight), so that
  // prediction = sum weight * profile(x_k + offset).
  template <typename Visit>
  void ForEachProbe(const Visit& visit) const {
    const auto wheel = [&](const wilcox::GridRun& run, double at, double sign) {
      if (patch_m <= 0.0) {
        visit(kTerrain, run, at, sign);
        return;
      }
      // WheelProfileAt: 5 points over the contact patch, weights 1 4 2 4 1 over 12.
      const double h = 0.25 * patch_m;
      static constexpr double kWeights[5] = {1.0, 4.0, 2.0, 4.0, 1.0};
      for (int q = 0; q < 5; ++q) visit(kTerrain, run, at + (q - 2) * h, sign * kWeights[q] / 12.0);
    };
    // The rear wheel's ride height, subtracted.
    wheel(y_near, 0.0, -1.0);
    visit(kSinkage, s_near, 0.0, 1.0);
    if (kind == kRange) {
      visit(kTerrain, y_far, offset_m, 1.0);
    } else {
      wheel(y_far, offset_m, 1.0);
      visit(kSinkage, s_far, offset_m, -1.0);
    }
  }

  template <typename T>
  bool operator()(T const* const* p, T* residual) const {
    const T& x = p[0][0];
    T const* const* y_p = p + 1;
    T const* const* s_p = y_p + y_blocks.size();
    T predicted = T(0.0);
    std::vector<const T*> nodes;
    ForEachProbe([&](Profile profile, const wilcox::GridRun& run, double offset, double weight) {
      NodePointers(run, profile == kTerrain ? y_blocks : s_blocks, profile == kTerrain ? y_p : s_p,
                   &nodes);
      predicted += weight * wilcox::ProfileAt(run, nodes.data(), T(x + offset));
    });
    residual[0] = (measured_m - predicted) / sd_m;
    return true;
  }

  // The cost function (analytic Jacobian); the caller adds the blocks in order: x, the y blocks,
  // the s blocks (Prepare called).
  static ceres::CostFunction* Create(const WilcoxMeasurementFactor& factor);

 private:
  std::vector<int> BlocksTouched(const wilcox::GridRun& a, const wilcox::GridRun& b) const {
    std::vector<int> blocks;
    for (const wilcox::GridRun* run : {&a, &b}) {
      if (run->count == 0) continue;
      for (int c = run->first / block_size; c <= (run->first + run->count - 1) / block_size; ++c) {
        blocks.push_back(c);
      }
    }
    std::sort(blocks.begin(), blocks.end());
    blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
    return blocks;
  }
  // Pointers to the run's nodes inside the blocks (node n: block n / block_size, element n % it).
  template <typename T>
  void NodePointers(const wilcox::GridRun& run, const std::vector<int>& blocks,
                    T const* const* block_values, std::vector<const T*>* nodes) const {
    nodes->resize(run.count);
    for (int j = 0; j < run.count; ++j) {
      const int n = run.first + j;
      (*nodes)[j] = block_values[SlotOf(blocks, n)] + n % block_size;
    }
  }
  int SlotOf(const std::vector<int>& blocks, int node) const {
    return static_cast<int>(std::lower_bound(blocks.begin(), blocks.end(), node / block_size) -
                            blocks.begin());
  }

  friend class WilcoxMeasurementCost;
};

// The factor with its analytic Jacobian: each probe w * profile(x + o) contributes w (1 - f) and
// w f to its two nodes and w * slope to x (0 where the probe is clamped to the run's end).
class WilcoxMeasurementCost : public ceres::CostFunction {
 public:
  explicit WilcoxMeasurementCost(const WilcoxMeasurementFactor& factor) : f_(factor) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(1);
    for (size_t i = 0; i < f_.y_blocks.size() + f_.s_blocks.size(); ++i) {
      mutable_parameter_block_sizes()->push_back(f_.block_size);
    }
  }

  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    const double x = p[0][0];
    const int y_count = static_cast<int>(f_.y_blocks.size());
    const int blocks = y_count + static_cast<int>(f_.s_blocks.size());
    if (jacobians != nullptr) {
      if (jacobians[0] != nullptr) jacobians[0][0] = 0.0;
      for (int b = 0; b < blocks; ++b) {
        if (jacobians[1 + b] != nullptr) std::fill_n(jacobians[1 + b], f_.block_size, 0.0);
      }
    }
    const double scale = -1.0 / f_.sd_m;  // d residual / d prediction
    double predicted = 0.0;
    f_.ForEachProbe([&](WilcoxMeasurementFactor::Profile profile, const wilcox::GridRun& run,
                        double offset, double weight) {
      const bool terrain = profile == WilcoxMeasurementFactor::kTerrain;
      const std::vector<int>& list = terrain ? f_.y_blocks : f_.s_blocks;
      const int first_slot = terrain ? 0 : y_count;
      // ProfileAt's interpolation, with its weights.
      double u = (x + offset) / run.spacing_m - run.first;
      bool clamped = false;
      if (u < 0.0) u = 0.0, clamped = true;
      if (u > run.count - 1) u = run.count - 1, clamped = true;
      const int i = std::min(static_cast<int>(std::floor(u)), run.count - 2);
      const double frac = u - i;
      const int n0 = run.first + i, n1 = n0 + 1;
      const int s0 = first_slot + f_.SlotOf(list, n0), s1 = first_slot + f_.SlotOf(list, n1);
      const double v0 = p[1 + s0][n0 % f_.block_size], v1 = p[1 + s1][n1 % f_.block_size];
      predicted += weight * ((1.0 - frac) * v0 + frac * v1);
      if (jacobians == nullptr) return;
      if (jacobians[0] != nullptr && !clamped) {
        jacobians[0][0] += scale * weight * (v1 - v0) / run.spacing_m;
      }
      if (jacobians[1 + s0] != nullptr) {
        jacobians[1 + s0][n0 % f_.block_size] += scale * weight * (1.0 - frac);
      }
      if (jacobians[1 + s1] != nullptr) {
        jacobians[1 + s1][n1 % f_.block_size] += scale * weight * frac;
      }
    });
    residuals[0] = (f_.measured_m - predicted) / f_.sd_m;
    return true;
  }

 private:
  WilcoxMeasurementFactor f_;
};

inline ceres::CostFunction* WilcoxMeasurementFactor::Create(const WilcoxMeasurementFactor& factor) {
  return new WilcoxMeasurementCost(factor);
}

}  // namespace slipgraph
