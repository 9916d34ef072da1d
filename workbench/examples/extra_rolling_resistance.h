// A force the model lacks, added by a program in one file: ground that resists rolling more than
// the model's rolling law says (a softer or stickier surface than the one its coefficients were
// measured on, a dragging brake, a bearing going dry), as a constant fraction theta of the weight
// against the motion,
//
//   a = -theta g sgn~(v),
//
// sgn~ the smooth sign the catalogue's resistances use (factors/catalogue_terms.h). A program adds
// it to the registry it hands to Diagnose (`registry.Add(ExtraRollingResistance())`); the
// walkthrough is docs/adding-an-effect.md, and tests/force_term_example_test.cpp checks it on a
// log simulated with the force.
//
// Evidence: to every sensor but the GNSS such a force looks like a lower velocity (the tire law
// pulls harder at more slip), so the smoother lowers v_bx by theta g over the tire law's slope
// while moving and the GNSS velocity disagrees with it wherever the robot drives; the graph score
// test of the shape sees that, and the velocity falling back at every stop.
#pragma once

#include "factors/catalogue_terms.h"
#include "factors/effect_term.h"
#include "factors/smooth_math.h"

namespace slipgraph {

struct ExtraRollingResistanceShape {
  template <typename T>
  T operator()(const T* x, const EffectContext&, const ward::Params& p) const {
    return -p.gravity_mps2 * SignedSaturation(x[ward::kVbx], kModelEffectSignRate);
  }
};

inline EffectTerm ExtraRollingResistance() {
  return MakeForceTerm<ExtraRollingResistanceShape>(
      "extra_rolling_resistance", "fraction of the weight", 0.3,
      "Ground that resists rolling more than the model's rolling law: a constant fraction of the "
      "weight against the motion. Its absence shows as a smoothed velocity below the GNSS's "
      "while moving (the tire law explains the missing force by more slip).");
}

}  // namespace slipgraph
