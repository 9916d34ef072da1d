#include "solvers/weak_constraints.h"

#include <algorithm>
#include <cmath>

namespace slipgraph {
namespace {

double Sign(double value) { return value > 0.0 ? 1.0 : (value < 0.0 ? -1.0 : 0.0); }

}  // namespace

bool MovingAgainstTheWheels(const double* x, double vel_dir) {
  return vel_dir != 0.0 && Sign(x[ward::kVbx]) == -vel_dir;
}

const char* WeakConstraintName(WeakConstraint constraint) {
  static const char* const kNames[kWeakConstraintCount] = {
      "oppose_motion", "act_quickly", "no_pull_back", "at_rest", "bound", "rate"};
  return kNames[static_cast<int>(constraint)];
}

void CollectWeakConstraints(const double* x, const double* x_prev, const WeakConstraintInputs& in,
                            const WeakConstraintConfig& c, std::vector<PseudoMeasurement>* out) {
  using namespace ward;  // NOLINT: state indices
  const double a_dist = x[kAdist];
  // WC1: the disturbance only opposes motion (doubted as the push grows: a Cauchy weight).
  if (in.vel_dir != 0.0 && Sign(a_dist) == in.vel_dir) {
    const double scale = c.oppose_motion_cauchy_scale_mps2;
    const double doubt = scale > 0.0 ? std::sqrt(1.0 + (a_dist / scale) * (a_dist / scale)) : 1.0;
    out->push_back({WeakConstraint::kOpposeMotion, kAdist, 0.0, c.sd_oppose_motion * doubt});
  }
  // WC2: a disturbance that grows slowly while slip stays small is decayed toward zero.
  if (in.slip_ema_rate_per_s > 0.0 && in.slip_ema_rate_per_s < c.min_slip_rate_per_s &&
      in.slip_ema < c.slip_threshold) {
    out->push_back({WeakConstraint::kActQuickly, kAdist, c.decay_alpha * a_dist, c.sd_act_quickly});
  }
  // WC3: the disturbance may stop the robot, not pull it backwards.
  if (MovingAgainstTheWheels(x, in.vel_dir)) {
    const double net_tire = in.f_tire_mps2 - in.gravity_along_x_mps2;
    if (Sign(net_tire) == -in.vel_dir) {
      out->push_back({WeakConstraint::kNoPullBack, kAdist, 0.0, c.sd_no_pull_back});
    } else {
      const double stopping = -net_tire;  // the disturbance that would just hold the robot
      const double z = in.vel_dir > 0.0 ? std::max(stopping, a_dist) : std::min(stopping, a_dist);
      out->push_back({WeakConstraint::kNoPullBack, kAdist, z, c.sd_no_pull_back});
    }
  }
  // WC4: at rest long enough, the walking biases and the disturbance tend to zero.
  if (in.wheels_stopped_s >= c.stop_time_s) {
    out->push_back({WeakConstraint::kAtRest, kAccelBias, 0.0, c.sd_at_rest});
    out->push_back({WeakConstraint::kAtRest, kAdist, 0.0, c.sd_at_rest});
    out->push_back({WeakConstraint::kAtRest, kGyroBias, 0.0, 0.1 * c.sd_at_rest});
  }
  // WC5: magnitude bounds.
  const struct {
    int index;
    double bound;
  } bounds[] = {{kVbx, c.max_v_bx_mps},
                {kAccelBias, c.max_accel_bias_mps2},
                {kAdist, c.max_a_dist_mps2},
                {kGyroBias, c.max_gyro_bias_radps}};
  for (const auto& b : bounds) {
    if (std::abs(x[b.index]) > b.bound) {
      out->push_back({WeakConstraint::kBound, b.index, Sign(x[b.index]) * b.bound, c.sd_bound});
    }
  }
  // WC6: rate bounds.
  if (in.dt_s > 0.0) {
    const struct {
      int index;
      double max_rate;
    } rates[] = {{kVbx, c.max_v_bx_rate_mps2}, {kAccelBias, c.max_accel_bias_rate_mps3}};
    for (const auto& r : rates) {
      const double change = x[r.index] - x_prev[r.index];
      if (std::abs(change) / in.dt_s > r.max_rate) {
        out->push_back({WeakConstraint::kRate, r.index,
                        x_prev[r.index] + Sign(change) * r.max_rate * in.dt_s, c.sd_bound});
      }
    }
  }
}

}  // namespace slipgraph
