// Automatic differentiation of a factor that reads only a few components of its parameter blocks
// (a soft prior on one state's a_dist, an encoder row on the wheel speeds): the Jets are as wide
// as the components read, not as the blocks. Ceres' AutoDiffCostFunction differentiates every
// component of every block, which for an encoder row on a 7-state is a 7-wide Jet for two
// non-zero columns; the window smoother evaluates such factors tens of times a second per state.
//
// The factor's functor is unchanged (the same templated operator() that AutoDiffCostFunction
// takes, one pointer per block); `Read` lists the components it reads:
//
//   struct EncoderReads {
//     static constexpr std::array<BlockComponent, 2> kComponents{{{0, ward::kOmegaLeft},
//                                                                {0, ward::kOmegaRight}}};
//   };
//   new ComponentAutoDiffCostFunction<EncoderFactor, EncoderReads, 2, ward::kStateSize>(functor)
//
// Every other component is passed as a constant, so its Jacobian column is zero: a list that
// misses a component the functor reads gives a wrong Jacobian. Each use is checked against
// AutoDiffCostFunction in tests/component_autodiff_test.cpp.
#pragma once

#include <ceres/jet.h>
#include <ceres/sized_cost_function.h>

#include <algorithm>
#include <array>
#include <memory>

namespace slipgraph {

struct BlockComponent {
  int block;      // the parameter block, in the cost function's order
  int component;  // its component
};

template <typename Functor, typename Read, int kResiduals, int... kBlockSizes>
class ComponentAutoDiffCostFunction final
    : public ceres::SizedCostFunction<kResiduals, kBlockSizes...> {
  static constexpr int kBlocks = sizeof...(kBlockSizes);
  static_assert(kBlocks == 1 || kBlocks == 2, "one or two parameter blocks");
  static constexpr int kRead = static_cast<int>(Read::kComponents.size());
  static constexpr std::array<int, kBlocks> kSizes{kBlockSizes...};
  // Each listed component inside its block, and listed once (a repeat would leave a column
  // written by one Jet direction and differentiated along two).
  static constexpr bool ValidComponents() {
    for (int k = 0; k < kRead; ++k) {
      const BlockComponent c = Read::kComponents[k];
      if (c.block < 0 || c.block >= kBlocks) return false;
      if (c.component < 0 || c.component >= kSizes[c.block]) return false;
      for (int j = 0; j < k; ++j) {
        const BlockComponent d = Read::kComponents[j];
        if (d.block == c.block && d.component == c.component) return false;
      }
    }
    return true;
  }
  static_assert(ValidComponents(), "a component outside its block, or listed twice");

 public:
  explicit ComponentAutoDiffCostFunction(Functor* functor) : functor_(functor) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    if (jacobians == nullptr) return Invoke(parameters, residuals);
    using Jet = ceres::Jet<double, kRead>;
    std::array<std::array<Jet, MaxSize()>, kBlocks> values;
    for (int b = 0; b < kBlocks; ++b) {
      for (int i = 0; i < kSizes[b]; ++i) values[b][i] = Jet(parameters[b][i]);
    }
    for (int k = 0; k < kRead; ++k) {
      const BlockComponent& c = Read::kComponents[k];
      values[c.block][c.component].v[k] = 1.0;
    }
    std::array<const Jet*, kBlocks> blocks;
    for (int b = 0; b < kBlocks; ++b) blocks[b] = values[b].data();
    std::array<Jet, kResiduals> out;
    if (!Invoke(blocks.data(), out.data())) return false;
    for (int r = 0; r < kResiduals; ++r) residuals[r] = out[r].a;
    for (int b = 0; b < kBlocks; ++b) {
      if (jacobians[b] == nullptr) continue;
      std::fill(jacobians[b], jacobians[b] + kResiduals * kSizes[b], 0.0);
    }
    for (int k = 0; k < kRead; ++k) {
      const BlockComponent& c = Read::kComponents[k];
      if (jacobians[c.block] == nullptr) continue;
      for (int r = 0; r < kResiduals; ++r) {
        jacobians[c.block][r * kSizes[c.block] + c.component] = out[r].v[k];
      }
    }
    return true;
  }

 private:
  static constexpr int MaxSize() {
    int size = 0;
    for (const int s : kSizes) size = s > size ? s : size;
    return size;
  }
  // The functor on one pointer per block, of doubles or of Jets.
  template <typename T>
  bool Invoke(const T* const* blocks, T* out) const {
    if constexpr (kBlocks == 1) {
      return (*functor_)(blocks[0], out);
    } else {
      return (*functor_)(blocks[0], blocks[1], out);
    }
  }
  std::unique_ptr<Functor> functor_;
};

}  // namespace slipgraph
