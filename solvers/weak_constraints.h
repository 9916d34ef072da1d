// The six weak constraints of Ward & Iagnemma, Table I, as pseudo-measurements: each returns the
// rows it applies now (which state, which pseudo-measurement value), or none when its condition
// does not hold. The EKF applies each row as a scalar measurement z = x[state] with variance
// sd^2; the smoother turns the same rules into smooth soft priors.
//
//   WC1 the disturbance only opposes motion: sign(a_dist) = VelDir != 0  -> a_dist := 0
//   WC2 the disturbance acts quickly: 0 < d(i_EMA)/dt < min, i_EMA < thresh
//                                                                      -> a_dist := alpha a_dist
//   WC3 it may stop the robot but not pull it backwards: sign(v) = -VelDir
//       a) sign(f_tire - g sin(phi)) = -VelDir                         -> a_dist := 0
//       b) otherwise                -> a_dist := max(VelDir (g sin(phi) - f_tire), a_dist)
//          (for VelDir = -1 the mirror image: min(...))
//   WC4 wheels stopped for t_stop: biases and disturbance to zero      -> b_ax, a_dist, b_gz := 0
//   WC5 magnitude bounds on v, b_ax, a_dist, b_gz                      -> x_i := sign(x_i) max_i
//   WC6 rate bounds on v, b_ax                   -> x_i := x_i,prev + sign(dx) max_rate dt
#pragma once

#include <vector>

#include "factors/drive_direction.h"
#include "factors/ward_state.h"
#include "model/model_config.h"

namespace slipgraph {

enum class WeakConstraint { kOpposeMotion = 0, kActQuickly, kNoPullBack, kAtRest, kBound, kRate };
constexpr int kWeakConstraintCount = 6;
const char* WeakConstraintName(WeakConstraint constraint);

struct PseudoMeasurement {
  WeakConstraint constraint;
  int state_index;
  double z;        // the value the state is pulled toward
  double density;  // sigma density (unit x sqrt(s)): variance sigma^2 / dt per cycle of dt
};

// Everything the conditions look at, besides the a priori state.
struct WeakConstraintInputs {
  double dt_s = 0.0;                  // since the previous filter cycle
  double vel_dir = 0.0;               // sign(w_l + w_r): +1, 0 or -1
  double slip_ema = 0.0;              // i_EMA
  double slip_ema_rate_per_s = 0.0;   // d(i_EMA)/dt
  double wheels_stopped_s = 0.0;      // how long both wheels have been still (0 unless still now)
  double f_tire_mps2 = 0.0;           // f_tire at the a priori wheel speeds, body held still
                                      // (v_bx = 0); read when MovingAgainstTheWheels
  double gravity_along_x_mps2 = 0.0;  // g sin(phi), phi uphill positive
};

// WC3's condition: the body moves against the wheels' direction. Only then does a constraint read
// WeakConstraintInputs::f_tire_mps2, so a caller may skip evaluating the tire forces otherwise.
bool MovingAgainstTheWheels(const double* x, double vel_dir);

// Appends the pseudo-measurements that apply at the a priori state x (and x_prev, the state of
// the previous cycle, for WC6).
void CollectWeakConstraints(const double* x, const double* x_prev, const WeakConstraintInputs& in,
                            const WeakConstraintConfig& config,
                            std::vector<PseudoMeasurement>* out);

}  // namespace slipgraph
