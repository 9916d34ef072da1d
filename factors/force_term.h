// A physical effect the catalogue does not have, added in one file: a force along the body's x
// axis, linear in one magnitude theta,
//
//   a_x = f_tire(x) + c_ax + b_ax + a_dist + theta h(x, c)          (m/s^2)
//
// where h is the force per unit magnitude and per unit mass, templated on the state's scalar (so
// the smoother differentiates it automatically), and c what the sample offers besides the state
// (its time, the attitude, the measured acceleration). A registered term is everything the
// workbench needs: the smoother adds it to the accelerometer's balance when a model names it
// (`effects: [NAME]`), with a weak prior of sd `prior_sd` on theta; `diagnose` tests it as a
// candidate (the score test of h on the whole graph) and `--with NAME` fits it. docs/adding-an-
// effect.md walks through one (workbench/examples/extra_rolling_resistance.cpp).
//
//   struct MyShape {
//     template <typename T>
//     T operator()(const T* x, const ForceTermContext& c, const ward::Params& p) const {...}
//   };
//   const ForceTermRegistration kMine(MakeForceTerm<MyShape>("my_effect", "unit", 1.0, "..."));
//
// A registration in a static library is dropped by the linker unless something references it:
// the file goes into the executable's sources.
#pragma once

#include <ceres/jet.h>

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "factors/ward_state.h"
#include "model/model_config.h"

namespace slipgraph {

// What a force term may use at one accelerometer sample besides the state.
struct ForceTermContext {
  double t_s = 0.0;
  ward::Attitude<double> attitude{0.0, 0.0};
  // The sample's measured x acceleration (for a shape that depends on the vehicle's
  // acceleration); NaN when the context is not an accelerometer sample.
  double accel_x_mps2 = std::numeric_limits<double>::quiet_NaN();
};

using ForceJet = ceres::Jet<double, ward::kStateSize>;

// h(x, c) on doubles and on the Jets the smoother differentiates with.
class ForceShape {
 public:
  virtual ~ForceShape() = default;
  virtual double operator()(const double* x, const ForceTermContext& c,
                            const ward::Params& p) const = 0;
  virtual ForceJet operator()(const ForceJet* x, const ForceTermContext& c,
                              const ward::Params& p) const = 0;
};

template <typename Shape>
class ForceShapeOf final : public ForceShape {
 public:
  explicit ForceShapeOf(Shape shape) : shape_(std::move(shape)) {}
  double operator()(const double* x, const ForceTermContext& c,
                    const ward::Params& p) const override {
    return shape_(x, c, p);
  }
  ForceJet operator()(const ForceJet* x, const ForceTermContext& c,
                      const ward::Params& p) const override {
    return shape_(x, c, p);
  }

 private:
  Shape shape_;
};

struct ForceTerm {
  std::string name;     // as models and `diagnose --with` name it
  std::string unit;     // theta's
  double prior_sd = 1;  // the weak prior on theta (around 0) once the term is on
  std::string physics;  // one paragraph: what the force is and what betrays its absence
  std::shared_ptr<const ForceShape> shape;
};

template <typename Shape>
ForceTerm MakeForceTerm(std::string name, std::string unit, double prior_sd, std::string physics,
                        Shape shape = Shape()) {
  return {std::move(name), std::move(unit), prior_sd, std::move(physics),
          std::make_shared<ForceShapeOf<Shape>>(std::move(shape))};
}

inline std::vector<ForceTerm>& ForceTermRegistry() {
  static std::vector<ForceTerm> terms;
  return terms;
}

// Every registered term, in registration order.
inline const std::vector<ForceTerm>& ForceTerms() { return ForceTermRegistry(); }

inline const ForceTerm* FindForceTerm(const std::string& name) {
  for (const ForceTerm& t : ForceTerms()) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

// Adds a term (a second one of the same name replaces the first) and makes its name valid in a
// model's `effects`.
inline void RegisterForceTerm(ForceTerm term) {
  RegisterModelEffectName(term.name);
  for (ForceTerm& t : ForceTermRegistry()) {
    if (t.name == term.name) {
      t = std::move(term);
      return;
    }
  }
  ForceTermRegistry().push_back(std::move(term));
}

struct ForceTermRegistration {
  explicit ForceTermRegistration(ForceTerm term) { RegisterForceTerm(std::move(term)); }
};

// The registered terms' summed acceleration at a state: sum_j theta_j h_j(x, c).
template <typename T>
T ForceTermsMps2(const std::vector<const ForceTerm*>& terms, const double* theta, const T* x,
                 const ForceTermContext& c, const ward::Params& p) {
  T sum = T(0.0);
  for (size_t j = 0; j < terms.size(); ++j) sum += theta[j] * (*terms[j]->shape)(x, c, p);
  return sum;
}

}  // namespace slipgraph
