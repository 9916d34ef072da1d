// A physical effect as a model term: one magnitude theta (0 = absent) and what it adds to the
// force balance the accelerometer sees,
//
//   a_x = f_tire(x) + c_ax + b_ax + a_dist + a_effects(theta, x, c)          (m/s^2)
//
// Each term is linear in its magnitude, of one of three kinds:
//   - force: an external force theta h(x, c) per unit mass (drag, turn slip, a resistance on
//     soft ground);
//   - slip: each driven side's relative velocity r w - v_fwd shifted by theta g(wheel, x, c) (a
//     rolling radius that is not the nominal one: g = r w);
//   - traction: each driven side's traction scaled by 1 + theta g(wheel, x, c) (a slope or a
//     terrain that changes the tire law, load transfer), g seeing the wheel after the slip terms.
// Together, per driven side i with normal force N_i and law F,
//
//   F_i' = F(N_i, v_rel_i + sum_slip theta g),   a_effects = sum_force theta h
//          + sum_i (F_i' (1 + sum_traction theta g) - F_i) / m.
//
// The shapes h and g are templated on the scalar (double and Ceres Jets), so the smoother
// differentiates them automatically; c is what the sample offers besides the state (its time,
// attitude, normal forces, measured acceleration, and whether it lies in the effect's windows).
//
// A term is everything the estimators and the workbench need: the smoother adds it to the
// accelerometer's balance when a model names it (`effects: [NAME]`), with a weak prior of sd
// `prior_sd` on theta; `diagnose` scores it as a candidate on the whole graph and `--with NAME`
// fits it. The catalogue's terms are factors/catalogue_terms.h; a program adds its own to an
// EffectTerms (docs/adding-an-effect.md):
//
//   struct MyShape {
//     template <typename T>
//     T operator()(const T* x, const EffectContext& c, const ward::Params& p) const {...}
//   };
//   terms.Add(MakeForceTerm<MyShape>("my_effect", "unit", 1.0, "what it is"));
#pragma once

#include <ceres/jet.h>

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "factors/traction.h"
#include "factors/ward_dynamics.h"
#include "factors/ward_state.h"

namespace slipgraph {

// What a term may use at one accelerometer sample besides the state.
struct EffectContext {
  double t_s = 0.0;
  ward::Attitude<double> attitude{0.0, 0.0};
  ward::AttitudeLoads<double> loads{};  // ComputeAttitudeLoads(attitude, params)
  // The sample's measured x acceleration (for a shape that depends on the vehicle's
  // acceleration); NaN when the context is not an accelerometer sample.
  double accel_x_mps2 = std::numeric_limits<double>::quiet_NaN();
  // For a term that acts on windows of the drive (EffectTerm::acts_on_windows): 1 inside one of
  // the model's windows for it (ModelConfig::effect_windows), 0 outside.
  double window = 0.0;
};

// The most effect terms one problem may hold: the Jets that differentiate them carry the state
// and every magnitude, the narrow ones up to 10 terms (as many as the catalogue has), the wide
// ones up to kMaxEffectTerms.
constexpr int kMaxEffectTerms = 16;
constexpr int kNarrowEffectTerms = 10;
using EffectJet = ceres::Jet<double, ward::kStateSize + kNarrowEffectTerms>;
using WideEffectJet = ceres::Jet<double, ward::kStateSize + kMaxEffectTerms>;

// One driven side as a slip or traction term sees it.
template <typename T>
struct WheelTraction {
  double normal_n;  // the side's driven wheels' normal force
  T v_rel_mps;      // r w - v_fwd (with the slip terms' shift, for a traction term)
  T rim_speed_mps;  // r w
  T traction_n;     // the law at v_rel
  T f_tire_mps2;    // the vehicle's f_tire with that traction on both sides
};

// h(x, c) of a force term, on doubles and on EffectJets.
class ForceShape {
 public:
  virtual ~ForceShape() = default;
  virtual double operator()(const double* x, const EffectContext& c,
                            const ward::Params& p) const = 0;
  virtual EffectJet operator()(const EffectJet* x, const EffectContext& c,
                               const ward::Params& p) const = 0;
  virtual WideEffectJet operator()(const WideEffectJet* x, const EffectContext& c,
                                   const ward::Params& p) const = 0;
};

// g(wheel, x, c) of a slip or traction term.
class WheelShape {
 public:
  virtual ~WheelShape() = default;
  virtual double operator()(const WheelTraction<double>& w, const double* x, const EffectContext& c,
                            const ward::Params& p) const = 0;
  virtual EffectJet operator()(const WheelTraction<EffectJet>& w, const EffectJet* x,
                               const EffectContext& c, const ward::Params& p) const = 0;
  virtual WideEffectJet operator()(const WheelTraction<WideEffectJet>& w, const WideEffectJet* x,
                                   const EffectContext& c, const ward::Params& p) const = 0;
};

enum class EffectKind { kForce, kSlip, kTraction };

struct EffectTerm {
  std::string name;     // as models and `diagnose --with` name it
  std::string unit;     // theta's
  double prior_sd = 1;  // the weak prior on theta (around 0) once the term is on
  std::string physics;  // one paragraph: what the effect is and what betrays its absence
  EffectKind kind = EffectKind::kForce;
  // true: it acts on windows of the drive only (soft ground, a changed terrain), which a model
  // that switches it on must give (ModelConfig::effect_windows).
  bool acts_on_windows = false;
  // true: it says a parameter of the model (a law's coefficient) is off rather than an effect is
  // missing; `diagnose` tests it only when asked (`--parameters`).
  bool model_parameter = false;
  std::shared_ptr<const ForceShape> force;  // kForce
  std::shared_ptr<const WheelShape> wheel;  // kSlip, kTraction
};

namespace effect_term_detail {

template <typename Shape>
class ForceShapeOf final : public ForceShape {
 public:
  explicit ForceShapeOf(Shape shape) : shape_(std::move(shape)) {}
  double operator()(const double* x, const EffectContext& c, const ward::Params& p) const override {
    return shape_(x, c, p);
  }
  EffectJet operator()(const EffectJet* x, const EffectContext& c,
                       const ward::Params& p) const override {
    return shape_(x, c, p);
  }
  WideEffectJet operator()(const WideEffectJet* x, const EffectContext& c,
                           const ward::Params& p) const override {
    return shape_(x, c, p);
  }

 private:
  Shape shape_;
};

template <typename Shape>
class WheelShapeOf final : public WheelShape {
 public:
  explicit WheelShapeOf(Shape shape) : shape_(std::move(shape)) {}
  double operator()(const WheelTraction<double>& w, const double* x, const EffectContext& c,
                    const ward::Params& p) const override {
    return shape_(w, x, c, p);
  }
  EffectJet operator()(const WheelTraction<EffectJet>& w, const EffectJet* x,
                       const EffectContext& c, const ward::Params& p) const override {
    return shape_(w, x, c, p);
  }
  WideEffectJet operator()(const WheelTraction<WideEffectJet>& w, const WideEffectJet* x,
                           const EffectContext& c, const ward::Params& p) const override {
    return shape_(w, x, c, p);
  }

 private:
  Shape shape_;
};

inline EffectTerm NamedTerm(EffectKind kind, std::string name, std::string unit, double prior_sd,
                            std::string physics) {
  EffectTerm t;
  t.name = std::move(name), t.unit = std::move(unit), t.prior_sd = prior_sd;
  t.physics = std::move(physics), t.kind = kind;
  return t;
}

template <typename Shape>
EffectTerm WheelTerm(EffectKind kind, std::string name, std::string unit, double prior_sd,
                     std::string physics, Shape shape) {
  EffectTerm t = NamedTerm(kind, std::move(name), std::move(unit), prior_sd, std::move(physics));
  t.wheel = std::make_shared<WheelShapeOf<Shape>>(std::move(shape));
  return t;
}

}  // namespace effect_term_detail

template <typename Shape>
EffectTerm MakeForceTerm(std::string name, std::string unit, double prior_sd, std::string physics,
                         Shape shape = Shape()) {
  EffectTerm t = effect_term_detail::NamedTerm(EffectKind::kForce, std::move(name), std::move(unit),
                                               prior_sd, std::move(physics));
  t.force = std::make_shared<effect_term_detail::ForceShapeOf<Shape>>(std::move(shape));
  return t;
}

template <typename Shape>
EffectTerm MakeSlipTerm(std::string name, std::string unit, double prior_sd, std::string physics,
                        Shape shape = Shape()) {
  return effect_term_detail::WheelTerm(EffectKind::kSlip, std::move(name), std::move(unit),
                                       prior_sd, std::move(physics), std::move(shape));
}

template <typename Shape>
EffectTerm MakeTractionTerm(std::string name, std::string unit, double prior_sd,
                            std::string physics, Shape shape = Shape()) {
  return effect_term_detail::WheelTerm(EffectKind::kTraction, std::move(name), std::move(unit),
                                       prior_sd, std::move(physics), std::move(shape));
}

// a_effects(theta, x, c) of the terms (header), T double, EffectJet or WideEffectJet. contexts: one
// per term (its window weight set).
template <typename T>
T EffectsAcceleration(const std::vector<const EffectTerm*>& terms, const T* theta, const T* x,
                      const std::vector<EffectContext>& contexts, const ward::Params& p) {
  T force = T(0.0);
  bool wheels = false;
  for (size_t j = 0; j < terms.size(); ++j) {
    if (terms[j]->kind == EffectKind::kForce) {
      force += theta[j] * (*terms[j]->force)(x, contexts[j], p);
    } else {
      wheels = true;
    }
  }
  if (!wheels) return force;
  const ward::AttitudeLoads<double>& loads = contexts.front().loads;
  const ward::TireForces<T> f = ward::ComputeTireForces(x, loads, p);
  WheelTraction<T> side[2] = {
      {loads.driven_left_n, f.v_rel_left_mps, x[ward::kOmegaLeft] * p.wheel_radius_m,
       f.traction_left_n, f.f_tire_mps2},
      {loads.driven_right_n, f.v_rel_right_mps, x[ward::kOmegaRight] * p.wheel_radius_m,
       f.traction_right_n, f.f_tire_mps2}};
  // sum_j theta_j g_j(side i) over the terms of one kind, per side.
  const auto SumOf = [&](EffectKind kind, T* sum) {
    sum[0] = sum[1] = T(0.0);
    for (size_t j = 0; j < terms.size(); ++j) {
      if (terms[j]->kind != kind) continue;
      for (int i = 0; i < 2; ++i)
        sum[i] += theta[j] * (*terms[j]->wheel)(side[i], x, contexts[j], p);
    }
  };
  T shift[2], scale[2];
  SumOf(EffectKind::kSlip, shift);
  T change = T(0.0);  // traction added by the slip terms, N
  for (int i = 0; i < 2; ++i) {
    side[i].v_rel_mps += shift[i];
    const T shifted = TractionForceN(side[i].normal_n, side[i].v_rel_mps, p.tire);
    change += shifted - side[i].traction_n;
    side[i].traction_n = shifted;
  }
  for (int i = 0; i < 2; ++i) side[i].f_tire_mps2 += change / p.mass_kg;
  SumOf(EffectKind::kTraction, scale);
  return force +
         (change + side[0].traction_n * scale[0] + side[1].traction_n * scale[1]) / p.mass_kg;
}

// The terms a program's estimators know, by name: built by the caller (CatalogueTerms() in
// factors/catalogue_terms.h, plus its own) and handed to the problems that use them.
class EffectTerms {
 public:
  // Adds a term; one of the same name is replaced.
  void Add(EffectTerm term) {
    for (EffectTerm& t : terms_) {
      if (t.name == term.name) {
        t = std::move(term);
        return;
      }
    }
    terms_.push_back(std::move(term));
  }
  // nullptr when no term has that name.
  const EffectTerm* Find(const std::string& name) const {
    for (const EffectTerm& t : terms_) {
      if (t.name == name) return &t;
    }
    return nullptr;
  }
  const std::vector<EffectTerm>& all() const { return terms_; }
  size_t size() const { return terms_.size(); }

 private:
  std::vector<EffectTerm> terms_;
};

}  // namespace slipgraph
