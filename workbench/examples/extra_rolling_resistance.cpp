// A force the model lacks, added in one file: ground that resists rolling more than the model's
// rolling law says (a softer or stickier surface than the one its coefficients were measured on,
// a dragging brake, a bearing going dry), as a constant fraction theta of the weight against
// the motion,
//
//   a = -theta g sgn~(v),
//
// sgn~ the smooth sign the catalogue's resistances use (factors/model_effects.h). The walkthrough
// is docs/adding-an-effect.md; tests/force_term_example_test.cpp builds this file into its test
// and checks it on a log simulated with the force.
//
// Evidence: to every sensor but the GNSS such a force looks like a lower velocity (the tire law
// pulls harder at more slip), so the smoother lowers v_bx by theta g over the tire law's slope
// while moving and the GNSS velocity disagrees with it wherever the robot drives; the graph score
// test of the shape sees that, and the velocity falling back at every stop.
#include <cmath>

#include "factors/force_term.h"
#include "factors/model_effects.h"
#include "factors/smooth_math.h"

namespace slipgraph {
namespace {

struct ExtraRollingResistance {
  template <typename T>
  T operator()(const T* x, const ForceTermContext&, const ward::Params& p) const {
    return -p.gravity_mps2 * SignedSaturation(x[ward::kVbx], kModelEffectSignRate);
  }
};

const ForceTermRegistration kExtraRollingResistance(MakeForceTerm<ExtraRollingResistance>(
    "extra_rolling_resistance", "fraction of the weight", 0.3,
    "Ground that resists rolling more than the model's rolling law: a constant fraction of the "
    "weight against the motion. Its absence shows as a smoothed velocity below the GNSS's "
    "while moving (the tire law explains the missing force by more slip)."));

}  // namespace
}  // namespace slipgraph
