#include "sim/skid_steer_sim.h"

#include <cmath>
#include <random>

#include "factors/ipd_kinematics.h"
#include "factors/slip_ratio.h"
#include "sim/command_schedule.h"
#include "sim/random.h"
#include "sim/sensor_models.h"

namespace slipgraph {
namespace sim {
namespace {

constexpr double kGravity = 9.80665;
constexpr double kTrackLagS = 0.15;         // drive response time constant
constexpr double kSlipNoiseTauS = 0.1;      // correlation time of the stochastic slip
constexpr double kImuBandwidthTauS = 0.01;  // IMU anti-alias filter on acceleration

}  // namespace

SimResult SimulateSkidSteer(const Scenario& sc, uint64_t seed) {
  std::mt19937_64 rng(seed);
  UnitNormal unit;
  SimResult result;
  DriveLog& log = result.log;
  log.vehicle = sc.vehicle;
  log.present_files = {"vehicle.yaml", "imu.csv", "wheels.csv", "truth.csv"};

  const Vehicle& veh = sc.vehicle;
  const double dt = sc.sim_step_s;
  const double c = veh.track_width_m;
  const double r_nominal = veh.wheel_radius_m;
  const double r_true = r_nominal * (1.0 + EffectValue(sc.effects, "wheel_radius_error"));
  result.true_wheel_radius_m = r_true;
  const double duration = sc.duration_s();

  SensorSimulator sensors(sc.sensors, sc.effects, 2, dt, &rng, &log);
  result.imu_errors = sensors.imu_errors();
  const int64_t truth_period = std::llround(1.0 / (sc.sensors.truth_rate_hz * dt));
  const int64_t steps = std::llround(duration / dt);
  const double steps_per_s = std::round(1.0 / dt);

  CommandSchedule commands(sc);
  KinematicState state;
  double s = 0.0;
  double noise[3] = {0.0, 0.0, 0.0};
  double previous_v[2] = {0.0, 0.0};
  const double decay = std::exp(-dt / kSlipNoiseTauS);

  for (int64_t k = 0; k <= steps; ++k) {
    const double t = k / steps_per_s;
    commands.Step(t, dt);
    const double v_cmd = commands.v_mps(), w_cmd = commands.yaw_rate_radps();
    const double target[2] = {(v_cmd - 0.5 * c * w_cmd) / r_nominal,
                              (v_cmd + 0.5 * c * w_cmd) / r_nominal};
    for (int side = 0; side < 2; ++side) {
      state.omega_radps[side] += (target[side] - state.omega_radps[side]) * dt / kTrackLagS;
    }

    // Nominal (odometry) velocity from the true track speeds and the true sprocket radius.
    const double v_n = 0.5 * r_true * (state.omega_radps[0] + state.omega_radps[1]);
    const double w_n = r_true * (state.omega_radps[1] - state.omega_radps[0]) / c;
    const TerrainType& terrain = sc.course.PatchAt(s).terrain;
    const double grade = sc.course.GradeRad(s);
    state.pitch = -grade;
    state.roll = sc.course.CrossSlopeRad(s);
    double g_x, g_y;
    ipd::GravityInBody(state.roll, state.pitch, kGravity, &g_x, &g_y);
    double u[3];
    ipd::SlipVelocities(v_n, w_n, g_x, g_y, terrain.ipd.alpha.data(), u);
    // Stochastic slip: Gauss-Markov with low-frequency density q = 2 sd^2 tau.
    for (int i = 0; i < 3; ++i) {
      const double sd = std::sqrt(terrain.ipd.q_density[i] / (2.0 * kSlipNoiseTauS));
      noise[i] = noise[i] * decay + sd * std::sqrt(1.0 - decay * decay) * unit(rng);
      u[i] += noise[i];
    }
    u[0] += v_n;
    u[2] += w_n;

    state.t = t;
    state.v_bx = u[0], state.v_by = u[1], state.yaw_rate = u[2];
    if (k > 0) {
      state.a_bx += ((u[0] - previous_v[0]) / dt - state.a_bx) * dt / kImuBandwidthTauS;
      state.a_by += ((u[1] - previous_v[1]) / dt - state.a_by) * dt / kImuBandwidthTauS;
    }
    previous_v[0] = u[0], previous_v[1] = u[1];
    state.command_v_mps = v_cmd;
    state.command_yaw_rate_radps = w_cmd;
    sensors.Observe(state, k);
    if (k % truth_period == 0) {
      TruthSample truth;
      truth.t = t;
      truth.x = state.x, truth.y = state.y, truth.z = state.z;
      truth.roll = state.roll, truth.pitch = state.pitch, truth.yaw = state.yaw;
      truth.vx = u[0], truth.vy = u[1], truth.yaw_rate = u[2];
      truth.a_dist = kMissing;  // no disturbance force in this kinematic model
      truth.immobilized = 0.0;
      truth.slip.fill(kMissing);
      truth.sinkage.fill(kMissing);
      for (int side = 0; side < 2; ++side) {
        const double v_fwd = u[0] + (side == 0 ? -0.5 : 0.5) * c * u[2];
        truth.slip[side] = SlipRatio(r_true * state.omega_radps[side], v_fwd);
      }
      log.truth.push_back(truth);
    }

    double rho_dot[3];
    ipd::PoseRate(state.roll, state.pitch, state.yaw, u, rho_dot);
    state.x += rho_dot[0] * dt;
    state.y += rho_dot[1] * dt;
    state.yaw += rho_dot[2] * dt;
    state.z += u[0] * std::sin(grade) * dt;
    for (int side = 0; side < 2; ++side)
      state.wheel_angle_rad[side] += state.omega_radps[side] * dt;
    const double previous_roll = state.roll, previous_pitch = state.pitch;
    s += u[0] * dt;  // signed: reversing moves back along the path
    state.roll_rate = (sc.course.CrossSlopeRad(s) - previous_roll) / dt;
    state.pitch_rate = (-sc.course.GradeRad(s) - previous_pitch) / dt;
  }
  return result;
}

}  // namespace sim
}  // namespace slipgraph
