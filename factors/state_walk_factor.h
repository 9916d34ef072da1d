// Random walk of chosen state components between consecutive Ward states, rows of Ward &
// Iagnemma eq. (10) (x_i' = 0 plus noise) as factors of their own so they can carry a robust
// loss:
//
//   r_j = (x_{k+1}[i_j] - x_k[i_j]) / (q sqrt(dt))   for each index i_j
//
// Parameter blocks: x_k (7), x_{k+1} (7).
//
// DisturbanceWalkFactor (a_dist): use with a robust ceres::LossFunction (Huber/Cauchy): a
// hold-back is a jump, not a Gaussian increment; the loss lets a few steps carry it, which in the
// smoother plays the part of weak constraint 2 ("the disturbance acts quickly").
//
// WheelSpeedWalkFactor (w_l, w_r): the wheels of a speed-controlled robot hold their speed and
// then step to a new one; a Gaussian walk stiff enough to average out encoder noise cannot follow
// the steps, a loose one follows the noise (docs/smoother.md). With a Huber loss a small q smooths
// the noise and the steps pass through a few large increments.
#pragma once

#include <ceres/sized_cost_function.h>

#include <algorithm>

#include "factors/ward_state.h"

namespace slipgraph {

template <int... kIndices>
struct StateWalkFactor {
  static constexpr int kResiduals = sizeof...(kIndices);

  explicit StateWalkFactor(double sd_per_step) : sqrt_information_(1.0 / sd_per_step) {}

  template <typename T>
  bool operator()(const T* x_k, const T* x_next, T* residual) const {
    int j = 0;
    ((residual[j++] = sqrt_information_ * (x_next[kIndices] - x_k[kIndices])), ...);
    return true;
  }

  // The residual is linear: its Jacobian is written out (+-1 / sd on the walked components)
  // rather than differentiated. Checked numerically in tests/soft_priors_test.cpp.
  static ceres::CostFunction* Create(double sd_per_step) { return new Cost(sd_per_step); }

 private:
  class Cost final
      : public ceres::SizedCostFunction<kResiduals, ward::kStateSize, ward::kStateSize> {
   public:
    explicit Cost(double sd_per_step) : walk_(sd_per_step) {}
    bool Evaluate(double const* const* parameters, double* residuals,
                  double** jacobians) const override {
      walk_(parameters[0], parameters[1], residuals);
      if (jacobians == nullptr) return true;
      constexpr int kIndex[] = {kIndices...};
      for (int b = 0; b < 2; ++b) {
        if (jacobians[b] == nullptr) continue;
        std::fill(jacobians[b], jacobians[b] + kResiduals * ward::kStateSize, 0.0);
        for (int j = 0; j < kResiduals; ++j) {
          jacobians[b][j * ward::kStateSize + kIndex[j]] =
              b == 0 ? -walk_.sqrt_information_ : walk_.sqrt_information_;
        }
      }
      return true;
    }

   private:
    StateWalkFactor walk_;
  };

  double sqrt_information_;
};

using DisturbanceWalkFactor = StateWalkFactor<ward::kAdist>;
using WheelSpeedWalkFactor = StateWalkFactor<ward::kOmegaLeft, ward::kOmegaRight>;

}  // namespace slipgraph
