#include "sim/diff_drive_sim.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "factors/normal_forces.h"
#include "factors/rolling_resistance.h"
#include "factors/slip_ratio.h"
#include "factors/smooth_math.h"
#include "factors/traction.h"
#include "sim/command_schedule.h"
#include "sim/peaked_tire.h"
#include "sim/sensor_models.h"

namespace slipgraph {
namespace sim {
namespace {

constexpr double kGravity = 9.80665;
// Truth labels (Ward & Iagnemma's "complete stop with the wheels still spinning"): immobilized
// when the body is stopped (below kStoppedSpeedMps) while the driven wheels turn (surface speed
// above kTurningWheelSpeedMps) at least twice as fast as the body moves (slip of 50 % or more).
constexpr double kStoppedSpeedMps = 0.03;
constexpr double kTurningWheelSpeedMps = 0.05;
constexpr double kMinEventS = 0.2;
// A stop interrupted for less than this is one event (a held robot rocking on its tether lifts
// its speed above kStoppedSpeedMps for a few samples).
constexpr double kMergeGapS = 0.5;
// Sinkage builds up over this distance into a soft patch.
constexpr double kSinkageBuildUpM = 0.5;
constexpr double kCorrugationWavelengthM = 0.8;
// Smoothing rate of sign(v) in the effect forces, 1/(m/s).
constexpr double kEffectSignRate = 20.0;

class EventTracker {
 public:
  void Update(double t, bool immobilized, std::vector<Event>* events) {
    if (immobilized && !active_) {
      // Joins the last event when it ended less than kMergeGapS ago.
      if (!events->empty() && t - events->back().t_end < kMergeGapS) {
        start_ = events->back().t_start;
        events->pop_back();
      } else {
        start_ = t;
      }
    }
    if (!immobilized && active_ && t - start_ >= kMinEventS) {
      events->push_back({start_, t, "immobilized"});
    }
    active_ = immobilized;
  }
  void Finish(double t, std::vector<Event>* events) { Update(t, false, events); }

 private:
  bool active_ = false;
  double start_ = 0.0;
};

}  // namespace

SimResult SimulateDiffDrive(const Scenario& sc, uint64_t seed) {
  std::mt19937_64 rng(seed);
  SimResult result;
  DriveLog& log = result.log;
  log.vehicle = sc.vehicle;
  // vehicle.yaml states the encoder noise simulated here, quantization included (4096 counts/rev
  // at 100 Hz: 0.066 rad/s, not the 0.05 the vehicle's sheet says). With the sheet's value the
  // smoother followed the encoders' rounding and its velocity came out 4 mm/s low while moving
  // on hidden/none, which the workbench then took for drag (docs/workbench.md).
  log.vehicle.sensors.wheels_sd_omega_radps = EncoderSpeedSd(sc.sensors);
  log.present_files = {"vehicle.yaml", "imu.csv", "wheels.csv", "truth.csv", "events.csv"};

  const Vehicle& veh = sc.vehicle;
  const EffectSet& fx = sc.effects;
  const Actuation& act = sc.actuation;
  const double dt = sc.sim_step_s;
  const double m = veh.mass_kg;
  const double weight = m * kGravity;
  const double c = veh.track_width_m;
  const double r_nominal = veh.wheel_radius_m;
  const double r_true = r_nominal * (1.0 + EffectValue(fx, "wheel_radius_error"));
  result.true_wheel_radius_m = r_true;
  const double duration = sc.duration_s();

  SensorSimulator sensors(sc.sensors, fx, 2, dt, &rng, &log);
  result.imu_errors = sensors.imu_errors();
  const int64_t truth_period = std::llround(1.0 / (sc.sensors.truth_rate_hz * dt));
  const int64_t steps = std::llround(duration / dt);

  KinematicState state;
  double s = 0.0;  // signed distance along the path (the course is a function of it)
  CommandSchedule commands(sc);
  double a_prev = 0.0;
  double integral[2] = {0.0, 0.0};
  double previous_roll = 0.0, previous_pitch = 0.0;
  double kappa[2] = {0.0, 0.0};  // slip ratios of the peaked law (mismatch suites)
  const auto level = DiffDriveCastorNormalForcesN(weight, 0.0, 0.0, veh.cg_to_front_m,
                                                  veh.cg_to_rear_m, c, veh.cg_height_m);
  int active_hold = -1;
  double hold_anchor_s = 0.0;
  EventTracker events;

  // k / rate rather than k * dt: the division is correctly rounded, so stamps print as 8.7, not
  // 8.700000000000001.
  const double steps_per_s = std::round(1.0 / dt);
  for (int64_t k = 0; k <= steps; ++k) {
    const double t = k / steps_per_s;
    commands.Step(t, dt);
    const double v_cmd = commands.v_mps(), w_cmd = commands.yaw_rate_radps();

    // Terrain under the vehicle.
    TerrainType terrain = sc.course.PatchAt(s).terrain;
    if (EffectValue(fx, "terrain_change") != 0.0 && t >= 0.5 * duration) {
      terrain.tire.C1 *= EffectValue(fx, "terrain_change");
      terrain.tire.C2 *= EffectValue(fx, "terrain_change");
    }
    const double grade = sc.course.GradeRad(s);  // uphill positive (Ward's phi)
    const double cross = sc.course.CrossSlopeRad(s);
    TireParams tire = terrain.tire;
    const double slope_scale =
        std::max(0.05, 1.0 - EffectValue(fx, "slope_slip") * std::abs(grade));
    tire.C1 *= slope_scale;
    std::optional<PeakedSoil> peaked = terrain.peaked;
    if (peaked) {
      // The effects that scale eq. (8)'s C1 scale the peaked law's peak.
      peaked->peak_mu *= slope_scale;
      if (EffectValue(fx, "terrain_change") != 0.0 && t >= 0.5 * duration) {
        peaked->peak_mu *= EffectValue(fx, "terrain_change");
      }
    }

    // Normal forces (eqs. 3-5), plus load transfer under acceleration when switched on.
    const auto n = DiffDriveCastorNormalForcesN(weight, cross, grade, veh.cg_to_front_m,
                                                veh.cg_to_rear_m, c, veh.cg_height_m);
    const double transfer = EffectValue(fx, "load_transfer") * m * a_prev * veh.cg_height_m /
                            (veh.cg_to_front_m + veh.cg_to_rear_m) / 2.0;
    const double n_front[2] = {n.front_left_n - transfer, n.front_right_n - transfer};
    const double n_rear_each = n.rear_each_n + transfer;

    // Tire forces on each side (0 = left, 1 = right).
    const double v = state.v_bx, yaw_rate = state.yaw_rate;
    const double v_fwd[2] = {v - 0.5 * c * yaw_rate, v + 0.5 * c * yaw_rate};
    double traction[2], rolling_front[2], rolling_side[2], r_eff[2];
    for (int side = 0; side < 2; ++side) {
      r_eff[side] = r_true;
      if (!peaked) {
        const double v_rel = TireRelativeVelocityMps(state.omega_radps[side], r_true, v_fwd[side]);
        traction[side] = TractionForceN(n_front[side], v_rel, tire);
        rolling_front[side] = RollingResistanceForceN(n_front[side], v_fwd[side], terrain.rolling);
        rolling_side[side] = rolling_front[side] +
                             RollingResistanceForceN(n_rear_each, v_fwd[side], terrain.rolling);
        continue;
      }
      const double load = n_front[side] / level.front_left_n - 1.0;
      r_eff[side] = r_true * (1.0 - sc.mismatch.radius_load_sensitivity * load);
      const double surface = r_eff[side] * state.omega_radps[side];
      kappa[side] = RelaxSlipRatio(kappa[side], SteadySlipRatio(surface, v_fwd[side]), v_fwd[side],
                                   surface, sc.mismatch.relaxation_length_m, dt);
      traction[side] = PeakedTractionForceN(n_front[side], kappa[side], *peaked);
      rolling_front[side] = PeakedRollingForceN(n_front[side], v_fwd[side], *peaked);
      rolling_side[side] =
          rolling_front[side] + PeakedRollingForceN(n_rear_each, v_fwd[side], *peaked);
    }

    // External forces: hold-back tether and the force-side effects.
    double f_external = 0.0;
    int hold = -1;
    for (size_t i = 0; i < sc.holdbacks.size(); ++i) {
      if (t >= sc.holdbacks[i].t_start_s && t < sc.holdbacks[i].t_end_s) hold = static_cast<int>(i);
    }
    if (hold != active_hold) hold_anchor_s = s;
    active_hold = hold;
    if (hold >= 0) {
      const double stretch = s - hold_anchor_s;  // the tether is slack until stretched
      if (stretch > 0.0) {
        f_external +=
            std::min(0.0, -(act.tether_stiffness_npm * stretch + act.tether_damping_nspm * v));
      }
    }
    const double sign_v = SignedSaturation(v, kEffectSignRate);
    f_external -= EffectValue(fx, "quadratic_drag") * v * std::abs(v);
    f_external -= EffectValue(fx, "turn_slip") * weight * std::abs(yaw_rate) * sign_v;
    if (terrain.soft) {
      const double build_up = std::min(1.0, sc.course.DistanceIntoPatch(s) / kSinkageBuildUpM);
      f_external -= EffectValue(fx, "sinkage_resistance") * weight * build_up * sign_v;
    }
    f_external +=
        EffectValue(fx, "corrugation") * m * std::sin(2.0 * M_PI * s / kCorrugationWavelengthM);
    if (sc.extra_force_n) {
      f_external += sc.extra_force_n({t, s, v, yaw_rate, grade, cross, m});
    }

    // Body dynamics (eqs. 1-2 with the true forces).
    const double a =
        (traction[0] + traction[1] + rolling_side[0] + rolling_side[1] + f_external) / m -
        kGravity * std::sin(grade);
    const double yaw_accel = c / (2.0 * veh.yaw_inertia_kgm2) *
                             (traction[1] + rolling_front[1] - traction[0] - rolling_front[0]);

    // Wheel-speed PI controllers with torque limit and anti-windup.
    const double target_omega[2] = {(v_cmd - 0.5 * c * w_cmd) / r_nominal,
                                    (v_cmd + 0.5 * c * w_cmd) / r_nominal};
    double omega_dot[2];
    for (int side = 0; side < 2; ++side) {
      const double error = target_omega[side] - state.omega_radps[side];
      integral[side] += error * dt;
      double torque = act.kp_nm_per_radps * error + act.ki_nm_per_rad * integral[side];
      if (std::abs(torque) > act.torque_limit_nm) {
        integral[side] -= error * dt;
        torque = std::copysign(act.torque_limit_nm, torque);
      }
      omega_dot[side] = (torque - r_eff[side] * traction[side]) / act.wheel_inertia_kgm2;
    }

    // Observe the state at t.
    state.t = t;
    state.pitch = -grade;  // REP-103 pitch is nose down positive
    state.roll = cross;
    state.roll_rate = k == 0 ? 0.0 : (state.roll - previous_roll) / dt;
    state.pitch_rate = k == 0 ? 0.0 : (state.pitch - previous_pitch) / dt;
    previous_roll = state.roll, previous_pitch = state.pitch;
    state.a_bx = a;
    state.command_v_mps = v_cmd;
    state.command_yaw_rate_radps = w_cmd;
    sensors.Observe(state, k);
    if (k % truth_period == 0) {
      const double surface_speed = 0.5 * (r_eff[0] * std::abs(state.omega_radps[0]) +
                                          r_eff[1] * std::abs(state.omega_radps[1]));
      const bool immobilized = surface_speed > kTurningWheelSpeedMps &&
                               std::abs(v) < kStoppedSpeedMps && 2.0 * std::abs(v) < surface_speed;
      events.Update(t, immobilized, &log.events);
      TruthSample truth;
      truth.t = t;
      truth.x = state.x, truth.y = state.y, truth.z = state.z;
      truth.roll = state.roll, truth.pitch = state.pitch, truth.yaw = state.yaw;
      truth.vx = v, truth.vy = 0.0, truth.yaw_rate = yaw_rate;
      truth.a_dist = f_external / m;
      truth.immobilized = immobilized ? 1.0 : 0.0;
      truth.slip.fill(kMissing);
      truth.sinkage.fill(kMissing);
      for (int side = 0; side < 2; ++side) {
        truth.slip[side] = SlipRatio(r_eff[side] * state.omega_radps[side], v_fwd[side]);
      }
      log.truth.push_back(truth);
    }

    // Integrate (semi-implicit Euler on a step far below every time constant).
    state.v_bx += a * dt;
    state.yaw_rate += yaw_accel * dt;
    for (int side = 0; side < 2; ++side) {
      state.omega_radps[side] += omega_dot[side] * dt;
      state.wheel_angle_rad[side] += state.omega_radps[side] * dt;
    }
    const double ground_speed = state.v_bx * std::cos(grade);
    state.x += ground_speed * std::cos(state.yaw) * dt;
    state.y += ground_speed * std::sin(state.yaw) * dt;
    state.z += state.v_bx * std::sin(grade) * dt;
    state.yaw += state.yaw_rate * dt;
    s += state.v_bx * dt;  // signed: reversing moves back along the path
    a_prev = a;
  }
  events.Finish(duration, &log.events);
  return result;
}

}  // namespace sim
}  // namespace slipgraph
