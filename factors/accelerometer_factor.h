// The accelerometer factor, Ward & Iagnemma eq. (11), row 1:
//
//   r = (a_x - (f_tire(x') + c_ax + b_ax + a_dist + sum_e a_e(theta_e, x, c))) / sd_a
//
// Parameter blocks: x_k (7) and the IMU offsets [c_ax, c_gz] (2), then, as a problem asks for
// them (AccelerometerUnknowns):
//   - law: the tire and rolling coefficients (kLawCoefficientCount) and the two sides' radius
//     errors (2), f_tire evaluated with them (factors/tire_law_coefficients.h; identify);
//   - stiffness: the law's slip stiffness as a slowly varying unknown theta(t), linear between
//     two nodes theta_a, theta_b (1 each): each driven wheel's traction is the law at the
//     relative velocity scaled by 1 + theta, which scales the law's slope at small slip
//     (C1 At + C2, where a robot drives) and leaves its plateau (C1, which a hold-back reaches);
//   - effects: the magnitudes of the model's effect terms (factors/effect_term.h), one block.
// The law excludes the other two; the stiffness walk and the effects go together (the workbench's
// null model with a law that varies along the path), the effects' slip and traction terms seeing
// the model's law unscaled (a term of order theta times the effect left out). Inputs: the attitude
// at the sample (REP-103 roll and pitch, rad); sd_a includes the tire law's uncertainty
// (ModelConfig::tire_uncertainty) when the accelerometer also drives the velocity. With the model's
// law the balance's Jacobian comes from f_tire's partials (4-wide Jets); with the law or the
// stiffness as unknowns, by automatic differentiation; the effect terms by Jets of the state and
// every magnitude (tests/accelerometer_factor_test.cpp checks every block's Jacobian numerically).
#pragma once

#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "factors/effect_term.h"
#include "factors/imu_factor.h"
#include "factors/tire_acceleration_partials.h"
#include "factors/tire_law_coefficients.h"
#include "factors/traction.h"

namespace slipgraph {

// The balance f_tire with the slip stiffness scaled by `scale` (1: the law's).
template <typename T, typename S>
inline T TireBalanceWithStiffness(const T* x, const ward::AttitudeLoads<double>& loads,
                                  const ward::Params& p, const S& scale) {
  const ward::TireForces<T> forces = ward::ComputeTireForces(x, loads, p);
  const T scaled = TractionForceN(loads.driven_left_n, scale * forces.v_rel_left_mps, p.tire) +
                   TractionForceN(loads.driven_right_n, scale * forces.v_rel_right_mps, p.tire);
  return forces.f_tire_mps2 +
         (scaled - forces.traction_left_n - forces.traction_right_n) / p.mass_kg;
}

// What the factor takes as unknowns besides the state and the offsets.
struct AccelerometerUnknowns {
  bool law = false;
  bool stiffness = false;
  double stiffness_share = 0.0;  // u: theta_b's share of the sample's theta
  // The effect terms, in the order of their magnitudes' block, and the sample's time and each
  // term's window weight (EffectContext::window; empty: 0 for all).
  std::vector<const EffectTerm*> effects;
  std::vector<double> windows;
  double t_s = 0.0;
};

namespace accelerometer_detail {

// The balance with the model's law: f_tire's partials from one 4-wide Jet pass
// (factors/tire_acceleration_partials.h), the rest of the residual linear.
class Plain final : public ceres::SizedCostFunction<1, ward::kStateSize, 2> {
 public:
  explicit Plain(const AccelerometerReading& reading) : reading_(reading) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* x = parameters[0];
    const double* offsets = parameters[1];
    if (jacobians == nullptr) {
      const ward::TireForces<double> forces =
          ward::ComputeTireForces(x, reading_.loads, reading_.params);
      residuals[0] = reading_.Residual(forces.f_tire_mps2, x, offsets);
      return true;
    }
    const ward::TireAccelerationPartials f =
        ward::TireAccelerationsWithPartials(x, reading_.loads, reading_.params).body_x;
    residuals[0] = reading_.Residual(f.value, x, offsets);
    const double w = -reading_.sqrt_information;
    if (jacobians[0] != nullptr) {
      double* j = jacobians[0];
      for (int i = 0; i < ward::kStateSize; ++i) j[i] = 0.0;
      j[ward::kVbx] = w * f.d_v_bx;
      j[ward::kAccelBias] = w;
      j[ward::kAdist] = w;
      j[ward::kOmegaLeft] = w * f.d_omega_left;
      j[ward::kOmegaRight] = w * f.d_omega_right;
      j[ward::kYawRate] = w * f.d_yaw_rate;
    }
    if (jacobians[1] != nullptr) {
      jacobians[1][0] = w;
      jacobians[1][1] = 0.0;
    }
    return true;
  }

 private:
  AccelerometerReading reading_;
};

struct Law {
  AccelerometerReading reading;
  template <typename T>
  bool operator()(const T* x, const T* offsets, const T* law, const T* radius_error,
                  T* residual) const {
    const ward::TireForces<T> forces =
        TireForcesWithLaw(x, reading.loads, reading.params, law, radius_error);
    residual[0] = reading.Residual(forces.f_tire_mps2, x, offsets);
    return true;
  }
};

struct Stiffness {
  AccelerometerReading reading;
  double share_b;
  template <typename T>
  bool operator()(const T* x, const T* offsets, const T* theta_a, const T* theta_b,
                  T* residual) const {
    const T scale = T(1.0) + (1.0 - share_b) * theta_a[0] + share_b * theta_b[0];
    residual[0] = reading.Residual(
        TireBalanceWithStiffness(x, reading.loads, reading.params, scale), x, offsets);
    return true;
  }
};

}  // namespace accelerometer_detail

class AccelerometerFactor final : public ceres::CostFunction {
 public:
  // Without effect terms the factor is the balance's automatic differentiation alone.
  static ceres::CostFunction* Create(const ward::Params& params,
                                     const ward::Attitude<double>& attitude, double accel_x_mps2,
                                     double sd_mps2, const AccelerometerUnknowns& unknowns = {}) {
    const AccelerometerReading reading(params, attitude, accel_x_mps2, sd_mps2);
    ceres::CostFunction* base = CreateBalance(reading, unknowns);
    if (unknowns.effects.empty()) return base;
    return new AccelerometerFactor(base, reading, attitude, unknowns);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    if (!base_->Evaluate(parameters, residuals, jacobians)) return false;
    const double* x = parameters[0];
    const double* theta = parameters[effect_block_];
    double* jacobian_x = jacobians != nullptr ? jacobians[0] : nullptr;
    double* jacobian_theta = jacobians != nullptr ? jacobians[effect_block_] : nullptr;
    if (jacobian_x == nullptr && jacobian_theta == nullptr) {
      residuals[0] -= reading_.sqrt_information *
                      EffectsAcceleration(effects_, theta, x, contexts_, reading_.params);
      return true;
    }
    if (effects_.size() <= static_cast<size_t>(kNarrowEffectTerms)) {
      AddEffects<EffectJet>(x, theta, residuals, jacobian_x, jacobian_theta);
    } else {
      AddEffects<WideEffectJet>(x, theta, residuals, jacobian_x, jacobian_theta);
    }
    return true;
  }

 private:
  // The effects' part of the residual and its Jacobians, by Jets J of the state and every
  // magnitude.
  template <typename J>
  void AddEffects(const double* x, const double* theta, double* residuals, double* jacobian_x,
                  double* jacobian_theta) const {
    const int n = static_cast<int>(effects_.size());
    J x_jet[ward::kStateSize];
    for (int i = 0; i < ward::kStateSize; ++i) x_jet[i] = J(x[i], i);
    J theta_jet[kMaxEffectTerms];
    for (int j = 0; j < n; ++j) theta_jet[j] = J(theta[j], ward::kStateSize + j);
    const J a = EffectsAcceleration(effects_, theta_jet, x_jet, contexts_, reading_.params);
    const double w = reading_.sqrt_information;
    residuals[0] -= w * a.a;
    if (jacobian_x != nullptr) {
      for (int i = 0; i < ward::kStateSize; ++i) jacobian_x[i] -= w * a.v[i];
    }
    if (jacobian_theta != nullptr) {
      for (int j = 0; j < n; ++j) jacobian_theta[j] = -w * a.v[ward::kStateSize + j];
    }
  }

  AccelerometerFactor(ceres::CostFunction* base, const AccelerometerReading& reading,
                      const ward::Attitude<double>& attitude, const AccelerometerUnknowns& unknowns)
      : base_(base), reading_(reading), effects_(unknowns.effects) {
    if (effects_.size() > static_cast<size_t>(kMaxEffectTerms)) {
      throw std::invalid_argument("accelerometer factor: " + std::to_string(effects_.size()) +
                                  " effect terms, at most " + std::to_string(kMaxEffectTerms));
    }
    EffectContext context;
    context.t_s = unknowns.t_s;
    context.attitude = attitude;
    context.loads = reading.loads;
    context.accel_x_mps2 = reading.measured;
    contexts_.assign(effects_.size(), context);
    for (size_t j = 0; j < effects_.size() && j < unknowns.windows.size(); ++j) {
      contexts_[j].window = unknowns.windows[j];
    }
    set_num_residuals(1);
    *mutable_parameter_block_sizes() = base->parameter_block_sizes();
    effect_block_ = static_cast<int>(parameter_block_sizes().size());
    mutable_parameter_block_sizes()->push_back(static_cast<int>(effects_.size()));
  }

  static ceres::CostFunction* CreateBalance(const AccelerometerReading& reading,
                                            const AccelerometerUnknowns& unknowns) {
    using namespace accelerometer_detail;
    if (unknowns.law && (unknowns.stiffness || !unknowns.effects.empty())) {
      throw std::invalid_argument(
          "accelerometer factor: the law as unknowns excludes the stiffness walk and effect "
          "terms");
    }
    if (unknowns.law) {
      return new ceres::AutoDiffCostFunction<Law, 1, ward::kStateSize, 2, kLawCoefficientCount, 2>(
          new Law{reading});
    }
    if (unknowns.stiffness) {
      return new ceres::AutoDiffCostFunction<Stiffness, 1, ward::kStateSize, 2, 1, 1>(
          new Stiffness{reading, unknowns.stiffness_share});
    }
    return new Plain(reading);
  }

  std::unique_ptr<ceres::CostFunction> base_;
  AccelerometerReading reading_;
  std::vector<const EffectTerm*> effects_;
  std::vector<EffectContext> contexts_;  // one per term: its window weight
  int effect_block_ = 2;
};

}  // namespace slipgraph
