// Physical effects as model terms: the estimator-side form of the catalogue's effects
// (model/effect_catalogue), each with one magnitude theta (0 = absent) in the unit the catalogue
// gives. They act on the tire-law balance the accelerometer sees,
//
//   a_x = f_tire(x') + c_ax + b_ax + a_dist + sum_e a_e(theta_e, x),
//
// where x' is the state with the wheel speeds scaled by (1 + wheel_radius_error) and the
// traction scaled by (1 - slope_slip |phi|):
//
//   quadratic_drag      a = -theta v |v| / m                       (N s^2/m^2)
//   turn_slip           a = -theta g |yaw rate| sgn~(v)            (s/rad)
//   slope_slip          traction x (1 - theta |phi|)               (1/rad)
//   wheel_radius_error  effective radius r (1 + theta)             (fraction)
//   sinkage_resistance  a = -theta g w_soft sgn~(v)                (fraction of weight)
//   terrain_change      traction x (1 + theta w_changed)           (relative change)
//   load_transfer       each driven front wheel's traction x (1 - theta m a h / (2 L N_i))
//                                                                   (scale)
//
// where, for load transfer (castor vehicles only: their driven wheels are the front pair and the
// castors take the load they lose; zero for the others), a is the body's acceleration the model
// gives the state, eq. (10)'s f_tire + a_dist - g sin(phi) (the measured a_x would do, but its
// noise and vibration make a regressor that biases the magnitude low: 4.4 for a true 6), and
// m a h / (2 L) the load each front wheel gives to the rear (h the CG height, L the wheelbase),
// as the simulator's effect;
// and w_soft is 1 on soft ground and w_changed 1 on the changed terrain, 0 elsewhere: the
// model's effect windows (ModelConfig::effect_windows, times the workbench found).
//
// sgn~ is the Jet-safe saturated sign the simulator uses. Templated on the state's and the
// magnitudes' scalar, so the Ceres factor and any other caller share one copy. The other
// catalogue effects have no model term yet (ModelEffectIndex returns -1 for them).
#pragma once

#include <array>
#include <cmath>
#include <string>

#include "factors/smooth_math.h"
#include "factors/ward_dynamics.h"
#include "model/model_config.h"

namespace slipgraph {

enum ModelEffect {
  kQuadraticDrag = 0,
  kTurnSlip,
  kSlopeSlip,
  kWheelRadiusError,
  kSinkageResistance,
  kTerrainChange,
  kLoadTransfer,
  kModelEffectCount
};

inline const std::array<const char*, kModelEffectCount>& ModelEffectNames() {
  static const std::array<const char*, kModelEffectCount> kNames = {
      "quadratic_drag",     "turn_slip",      "slope_slip",   "wheel_radius_error",
      "sinkage_resistance", "terrain_change", "load_transfer"};
  return kNames;
}

// Index of a catalogue effect among the model terms, or -1 when it has none yet.
inline int ModelEffectIndex(const std::string& name) {
  for (int i = 0; i < kModelEffectCount; ++i) {
    if (name == ModelEffectNames()[i]) return i;
  }
  return -1;
}

// Standard deviations of the weak prior on each magnitude (around 0) when the effect is switched
// on: several times the catalogue's typical value, so the data decide.
constexpr std::array<double, kModelEffectCount> kModelEffectPriorSd = {400.0, 1.0, 20.0, 0.3,
                                                                       0.3,   1.0, 10.0};

// The weights of the effects that act on windows of the drive (ActsOnWindows in
// model/model_config.h) at one sample: 1 inside one of the effect's windows, 0 outside.
struct EffectWindowWeights {
  double soft_ground = 0.0;      // sinkage_resistance
  double changed_terrain = 0.0;  // terrain_change
};
inline EffectWindowWeights EffectWindowWeightsAt(const ModelConfig& model, double t) {
  EffectWindowWeights w;
  w.soft_ground = model.InEffectWindow("sinkage_resistance", t) ? 1.0 : 0.0;
  w.changed_terrain = model.InEffectWindow("terrain_change", t) ? 1.0 : 0.0;
  return w;
}

// Rate of the saturated sign of v (1/(m/s)), as the simulator's effects use it.
constexpr double kModelEffectSignRate = 20.0;

// The effects that are external forces (drag, turn slip, sinkage resistance), as an
// acceleration (m/s^2): what a disturbance estimate no longer carries once they are in the
// model. soft_ground: w of sinkage_resistance at this sample (0 or 1).
template <typename T>
inline T ExternalEffectsMps2(const T* x, const ward::Params& p, const T* theta,
                             double soft_ground = 0.0) {
  using std::abs;
  const T v = x[ward::kVbx];
  const T sign = SignedSaturation(v, kModelEffectSignRate);
  return -theta[kQuadraticDrag] * v * abs(v) / p.mass_kg -
         theta[kTurnSlip] * p.gravity_mps2 * abs(x[ward::kYawRate]) * sign -
         theta[kSinkageResistance] * p.gravity_mps2 * soft_ground * sign;
}

// The accelerometer's model prediction without offsets, biases and a_dist: f_tire with the
// effects' terms. theta: kModelEffectCount magnitudes (inactive ones are 0); w: the windowed
// effects' weights at this sample.
// loads: ComputeAttitudeLoads(attitude, p), which a factor computes once.
template <typename T>
inline T TireBalanceWithEffects(const T* x, const ward::Attitude<double>& attitude,
                                const ward::AttitudeLoads<double>& loads, const ward::Params& p,
                                const T* theta, const EffectWindowWeights& w = {}) {
  using R = T;
  R state[ward::kStateSize];
  for (int i = 0; i < ward::kStateSize; ++i) state[i] = x[i];
  const R radius_scale = R(1.0) + theta[kWheelRadiusError];
  state[ward::kOmegaLeft] *= radius_scale;
  state[ward::kOmegaRight] *= radius_scale;
  const ward::TireForces<R> forces = ward::ComputeTireForces(state, loads, p);
  const double phi = std::abs(WardPitchUphillRad(attitude.pitch_rad));
  const R traction_n = forces.traction_left_n + forces.traction_right_n;
  R balance = forces.f_tire_mps2 +
              (theta[kTerrainChange] * w.changed_terrain - theta[kSlopeSlip] * phi) * traction_n /
                  p.mass_kg +
              ExternalEffectsMps2(state, p, theta, w.soft_ground);
  if (p.type == VehicleType::kDiffDriveCastor) {
    const R body_accel = forces.f_tire_mps2 + x[ward::kAdist] - loads.gravity_along_x_mps2;
    const R transfer_n = theta[kLoadTransfer] * p.mass_kg * body_accel * p.cg_height_m /
                         (2.0 * (p.cg_to_front_m + p.cg_to_rear_m));
    balance -= transfer_n *
               (forces.traction_left_n / loads.driven_left_n +
                forces.traction_right_n / loads.driven_right_n) /
               p.mass_kg;
  }
  return balance;
}

}  // namespace slipgraph
