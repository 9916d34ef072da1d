// The accelerometer factor of a model with registered force terms (factors/force_term.h) on:
//
//   r = (a_x - (f_tire(x; theta) + c_ax + b_ax + a_dist + sum_j phi_j h_j(x, c))) / sd_a
//
// Parameter blocks: x_k (7), IMU offsets [c_ax, c_gz] (2), the catalogue effects' magnitudes
// theta (kModelEffectCount), the registered terms' magnitudes phi (one each, in `terms` order).
// The catalogue part is EffectAccelerometerFactor's (automatic differentiation); each h_j is
// differentiated by its own 7-wide Jets. With phi = 0 it is EffectAccelerometerFactor exactly
// (tests/force_terms_accelerometer_factor_test.cpp, which also checks the Jacobian numerically).
#pragma once

#include <ceres/cost_function.h>

#include <memory>
#include <vector>

#include "factors/effect_accelerometer_factor.h"
#include "factors/force_term.h"

namespace slipgraph {

class ForceTermsAccelerometerFactor final : public ceres::CostFunction {
 public:
  ForceTermsAccelerometerFactor(const ward::Params& params, const ForceTermContext& context,
                                double sd_mps2, const EffectWindowWeights& windows,
                                std::vector<const ForceTerm*> terms)
      : catalogue_(EffectAccelerometerFactor::Create(params, context.attitude, context.accel_x_mps2,
                                                     sd_mps2, windows)),
        params_(params),
        context_(context),
        sqrt_information_(1.0 / sd_mps2),
        terms_(std::move(terms)) {
    set_num_residuals(1);
    *mutable_parameter_block_sizes() = {ward::kStateSize, 2, kModelEffectCount,
                                        static_cast<int>(terms_.size())};
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    double* catalogue_jacobians[3] = {nullptr, nullptr, nullptr};
    if (jacobians != nullptr) {
      for (int i = 0; i < 3; ++i) catalogue_jacobians[i] = jacobians[i];
    }
    if (!catalogue_->Evaluate(parameters, residuals,
                              jacobians != nullptr ? catalogue_jacobians : nullptr)) {
      return false;
    }
    const double* x = parameters[0];
    const double* phi = parameters[3];
    const bool want_x = jacobians != nullptr && jacobians[0] != nullptr;
    const bool want_phi = jacobians != nullptr && jacobians[3] != nullptr;
    ForceJet x_jet[ward::kStateSize];
    for (int i = 0; i < ward::kStateSize; ++i) x_jet[i] = ForceJet(x[i], i);
    for (size_t j = 0; j < terms_.size(); ++j) {
      const ForceShape& h = *terms_[j]->shape;
      double value = 0.0;
      if (want_x) {
        const ForceJet jet = h(x_jet, context_, params_);
        value = jet.a;
        for (int i = 0; i < ward::kStateSize; ++i) {
          jacobians[0][i] -= sqrt_information_ * phi[j] * jet.v[i];
        }
      } else {
        value = h(x, context_, params_);
      }
      residuals[0] -= sqrt_information_ * phi[j] * value;
      if (want_phi) jacobians[3][j] = -sqrt_information_ * value;
    }
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> catalogue_;
  ward::Params params_;
  ForceTermContext context_;
  double sqrt_information_;
  std::vector<const ForceTerm*> terms_;
};

}  // namespace slipgraph
