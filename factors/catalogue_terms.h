// The catalogue's physical effects as model terms (factors/effect_term.h), each with one
// magnitude theta (0 = absent) in the catalogue's unit:
//
//   quadratic_drag      force     h = -v |v| / m                      (N s^2/m^2)
//   turn_slip           force     h = -g |yaw rate| sgn~(v)           (s/rad)
//   sinkage_resistance  force     h = -g w sgn~(v)                    (fraction of weight)
//   wheel_radius_error  slip      g = r w: radius r (1 + theta)       (fraction)
//   slope_slip          traction  g = -|phi|                          (1/rad)
//   terrain_change      traction  g = w                               (relative change)
//   load_transfer       traction  g = -m a h / (2 L N)                (scale)
//
// and three terms that say a parameter of the model is off rather than an effect is missing
// (EffectTerm::model_parameter: `diagnose --parameters` tests them), each a relative change of
// what the model's laws give (1 + theta times it):
//
//   tire_traction_level       traction  g = 1: the law's traction, C1 and C2   (relative change)
//   tire_slip_stiffness       slip      g = v_rel: its slope at small slip     (relative change)
//   rolling_resistance_level  force     h = the rolling law's acceleration     (relative change)
//
// N is a driven side's normal force; phi the grade; w 1 inside the effect's windows (soft ground,
// the changed terrain; ModelConfig::effect_windows), 0 outside. Load transfer is the castor
// vehicle's (its driven wheels are the front pair and the castors take the load they lose; zero for
// the others): a is the body's acceleration the model gives the state, eq. (10)'s f_tire + a_dist -
// g sin(phi) (the measured a_x would do, but its noise and vibration make a regressor that biases
// the magnitude low: 4.4 for a true 6), h the CG height and L the wheelbase, as the simulator's
// effect. sgn~ is the Jet-safe saturated sign the simulator uses.
//
// A new catalogue effect is a shape here and one line in CatalogueTerms(), and its
// signature in workbench/effect_signatures.cpp (docs/adding-an-effect.md).
#pragma once

#include <cmath>

#include "factors/effect_term.h"
#include "factors/smooth_math.h"
#include "factors/traction.h"

namespace slipgraph {

// Rate of the saturated sign of v (1/(m/s)), as the simulator's effects use it.
constexpr double kModelEffectSignRate = 20.0;

namespace catalogue_terms {

struct QuadraticDrag {
  template <typename T>
  T operator()(const T* x, const EffectContext&, const ward::Params& p) const {
    using std::abs;
    return -x[ward::kVbx] * abs(x[ward::kVbx]) / p.mass_kg;
  }
};

struct TurnSlip {
  template <typename T>
  T operator()(const T* x, const EffectContext&, const ward::Params& p) const {
    using std::abs;
    return -p.gravity_mps2 * abs(x[ward::kYawRate]) *
           SignedSaturation(x[ward::kVbx], kModelEffectSignRate);
  }
};

struct SinkageResistance {
  template <typename T>
  T operator()(const T* x, const EffectContext& c, const ward::Params& p) const {
    return -p.gravity_mps2 * c.window * SignedSaturation(x[ward::kVbx], kModelEffectSignRate);
  }
};

struct WheelRadiusError {
  template <typename T>
  T operator()(const WheelTraction<T>& w, const T*, const EffectContext&,
               const ward::Params&) const {
    return w.rim_speed_mps;
  }
};

struct SlopeSlip {
  template <typename T>
  T operator()(const WheelTraction<T>&, const T*, const EffectContext& c,
               const ward::Params&) const {
    return T(-std::abs(WardPitchUphillRad(c.attitude.pitch_rad)));
  }
};

struct TerrainChange {
  template <typename T>
  T operator()(const WheelTraction<T>&, const T*, const EffectContext& c,
               const ward::Params&) const {
    return T(c.window);
  }
};

struct LoadTransfer {
  template <typename T>
  T operator()(const WheelTraction<T>& w, const T* x, const EffectContext& c,
               const ward::Params& p) const {
    if (p.type != VehicleType::kDiffDriveCastor) return T(0.0);
    const T body_accel = w.f_tire_mps2 + x[ward::kAdist] - c.loads.gravity_along_x_mps2;
    return -p.mass_kg * body_accel * p.cg_height_m /
           (2.0 * (p.cg_to_front_m + p.cg_to_rear_m) * w.normal_n);
  }
};

struct TractionLevel {
  template <typename T>
  T operator()(const WheelTraction<T>&, const T*, const EffectContext&, const ward::Params&) const {
    return T(1.0);
  }
};

struct SlipStiffness {
  template <typename T>
  T operator()(const WheelTraction<T>& w, const T*, const EffectContext&,
               const ward::Params&) const {
    return w.v_rel_mps;
  }
};

struct RollingLevel {
  template <typename T>
  T operator()(const T* x, const EffectContext& c, const ward::Params& p) const {
    const ward::TireForces<T> f = ward::ComputeTireForces(x, c.loads, p);
    return f.f_tire_mps2 - (f.traction_left_n + f.traction_right_n) / p.mass_kg;
  }
};

inline EffectTerm Windowed(EffectTerm term) {
  term.acts_on_windows = true;
  return term;
}

inline EffectTerm Parameter(EffectTerm term) {
  term.model_parameter = true;
  return term;
}

}  // namespace catalogue_terms

// The catalogue's terms, in the order the workbench reports them. The prior sd of each is
// several times the catalogue's typical magnitude, so the data decide.
inline const EffectTerms& CatalogueTerms() {
  static const EffectTerms kTerms = [] {
    using namespace catalogue_terms;
    EffectTerms t;
    t.Add(MakeForceTerm<QuadraticDrag>(
        "quadratic_drag", "N s^2/m^2", 400.0,
        "Aerodynamic or vegetation drag theta v |v| opposing motion: acceleration residuals that "
        "grow with v^2."));
    t.Add(MakeForceTerm<TurnSlip>(
        "turn_slip", "s/rad", 1.0,
        "Tire scrub in turns: theta m g |yaw rate| opposing motion, none when driving straight."));
    t.Add(MakeTractionTerm<SlopeSlip>(
        "slope_slip", "1/rad", 20.0,
        "Looser footing on inclines: traction x (1 - theta |grade|), residuals on slopes only."));
    t.Add(MakeSlipTerm<WheelRadiusError>(
        "wheel_radius_error", "fraction", 0.3,
        "The effective rolling radius is nominal x (1 + theta): a constant apparent slip that "
        "grows with speed."));
    t.Add(Windowed(MakeForceTerm<SinkageResistance>(
        "sinkage_resistance", "fraction of weight", 0.3,
        "Compaction resistance theta m g on soft ground (the model's windows), none on hard.")));
    t.Add(Windowed(MakeTractionTerm<TerrainChange>(
        "terrain_change", "relative change", 1.0,
        "The tire law's traction x (1 + theta) on the changed terrain (the model's windows).")));
    t.Add(MakeTractionTerm<LoadTransfer>(
        "load_transfer", "scale", 10.0,
        "Longitudinal load transfer theta m a h / L off the driven front wheels of a castor "
        "vehicle: traction residuals correlated with acceleration."));
    t.Add(Parameter(MakeTractionTerm<TractionLevel>(
        "tire_traction_level", "relative change", 1.0,
        "The tire law's traction (C1 and C2 together) is off by theta over the whole drive: the "
        "terrain "
        "holds more or less than the law says wherever the wheels pull hard.")));
    t.Add(Parameter(MakeSlipTerm<SlipStiffness>(
        "tire_slip_stiffness", "relative change", 1.0,
        "The tire law's slope at small slip (At, C2) is off by theta: the slip the wheels need "
        "for a force is not the law's, which a velocity bias at steady speed betrays.")));
    t.Add(Parameter(MakeForceTerm<RollingLevel>(
        "rolling_resistance_level", "relative change", 1.0,
        "The rolling law's resistance is off by theta: a force against the motion in proportion "
        "to the model's own rolling resistance.")));
    return t;
  }();
  return kTerms;
}

// The terms a caller gave, or the catalogue's when it gave none.
inline const EffectTerms& TermsOrCatalogue(const EffectTerms* terms) {
  return terms != nullptr ? *terms : CatalogueTerms();
}

}  // namespace slipgraph
