#include "sim/skid_steer_sim.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "factors/ipd_kinematics.h"
#include "factors/slip_ratio.h"
#include "sim/command_schedule.h"
#include "sim/peaked_tire.h"
#include "sim/random.h"
#include "sim/sensor_models.h"

namespace slipgraph {
namespace sim {
namespace {

constexpr double kGravity = 9.80665;
constexpr double kTrackLagS = 0.15;         // drive response time constant
constexpr double kSlipNoiseTauS = 0.1;      // correlation time of the stochastic slip
constexpr double kImuBandwidthTauS = 0.01;  // IMU anti-alias filter on acceleration

// The soil's variation under each track along the path (VehicleMismatch): unit Gauss-Markov
// processes in distance, for each track's strength and shear modulus.
struct SoilVariation {
  double strength[2] = {0.0, 0.0};
  double modulus[2] = {0.0, 0.0};

  // Each track's processes advance by the ground its line crossed (m); correlation_m > 0.
  void Advance(const double distance_m[2], double correlation_m, std::mt19937_64* rng,
               UnitNormal* unit) {
    for (int side = 0; side < 2; ++side) {
      const double moved = std::abs(distance_m[side]);
      strength[side] = GaussMarkovStep(strength[side], 1.0, correlation_m, moved, (*unit)(*rng));
      modulus[side] = GaussMarkovStep(modulus[side], 1.0, correlation_m, moved, (*unit)(*rng));
    }
  }
};

// What the track-soil model needs besides the body's velocity.
struct TrackInputs {
  double tread_mps[2];  // r w of each track
  double g_x, g_y;      // gravity in body axes
  double pitch, roll;
};

// The body's accelerations (dV_x, dV_yaw, dV_y) at velocity x = (V_x, V_yaw, V_y) over soil
// `soil` (sim/track_soil.h): the soil's shear under each track, rolling resistance, gravity.
void TrackSoilAcceleration(const Vehicle& veh, const TrackSoil& soil, const VehicleMismatch& mm,
                           const SoilVariation& variation, const TrackInputs& in, const double x[3],
                           double x_dot[3]) {
  const double v = x[0], w = x[1], v_y = x[2];
  const double b = veh.track_width_m;
  const double area = mm.tracks.belt_width_m * mm.tracks.contact_length_m;
  const double weight = veh.mass_kg * kGravity * std::cos(in.pitch) * std::cos(in.roll);
  const double lateral = v * w - in.g_y;  // specific force the ground gives sideways
  const double transfer = veh.mass_kg * lateral * veh.cg_height_m / b;
  const double load[2] = {std::max(0.5 * weight - transfer, 0.05 * weight),
                          std::max(0.5 * weight + transfer, 0.05 * weight)};
  const double sd = mm.track_soil_variation_sd;
  double force_x = 0.0, force_y = 0.0, moment = 0.0;
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? 0.5 * b : -0.5 * b;  // left, right
    const double strength =
        (soil.cohesion_pa + load[side] / area * std::tan(soil.friction_angle_rad)) *
        std::exp(sd * variation.strength[side]);
    const double modulus = soil.shear_modulus_m * std::exp(sd * variation.modulus[side]);
    const TrackForce f =
        TrackShear(in.tread_mps[side], v - y * w, v_y, w, strength, modulus, mm.tracks);
    force_x += f.x_n, force_y += f.y_n;
    moment += f.moment_nm - y * f.x_n;
  }
  const double rolling = RollingResistanceN(weight, v, soil.roll_c0, soil.roll_c1_spm);
  x_dot[0] = (force_x + rolling) / veh.mass_kg + in.g_x + v_y * w;
  x_dot[1] = moment / veh.yaw_inertia_kgm2;
  x_dot[2] = force_y / veh.mass_kg + in.g_y - v * w;
}

// One linearly implicit Euler step of the body's velocity (the shear laws are stiff at low speed):
// (I - dt J) dx = dt f(x), J by forward differences.
void StepTrackSoil(const Vehicle& veh, const TrackSoil& soil, const VehicleMismatch& mm,
                   const SoilVariation& variation, const TrackInputs& in, double dt, double x[3]) {
  double f[3];
  TrackSoilAcceleration(veh, soil, mm, variation, in, x, f);
  Eigen::Matrix3d jacobian;
  for (int i = 0; i < 3; ++i) {
    double shifted[3] = {x[0], x[1], x[2]};
    const double h = 1e-6 * (1.0 + std::abs(x[i]));
    shifted[i] += h;
    double f_shifted[3];
    TrackSoilAcceleration(veh, soil, mm, variation, in, shifted, f_shifted);
    for (int j = 0; j < 3; ++j) jacobian(j, i) = (f_shifted[j] - f[j]) / h;
  }
  const Eigen::Vector3d step = (Eigen::Matrix3d::Identity() - dt * jacobian)
                                   .partialPivLu()
                                   .solve(dt * Eigen::Vector3d(f[0], f[1], f[2]));
  for (int i = 0; i < 3; ++i) x[i] += step[i];
  if (!step.allFinite() || std::abs(x[0]) > 100.0 || std::abs(x[1]) > 100.0 ||
      std::abs(x[2]) > 100.0) {
    throw std::runtime_error("the track-soil model diverged (a simulator defect)");
  }
}

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
  // The track-soil model's state (ipd35m): the body's velocity (V_x, V_yaw, V_y), the soil's
  // variation, and its own random stream (ipd35's draws are unchanged).
  double body[3] = {0.0, 0.0, 0.0};
  std::mt19937_64 soil_rng(seed ^ 0x747261636b736f6cULL);
  UnitNormal soil_unit;
  SoilVariation variation;
  const double far[2] = {1e9, 1e9};
  variation.Advance(far, 1.0, &soil_rng, &soil_unit);  // start from the stationary spread

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
    if (terrain.track_soil) {
      TrackInputs inputs;
      for (int side = 0; side < 2; ++side)
        inputs.tread_mps[side] = r_true * state.omega_radps[side];
      inputs.g_x = g_x, inputs.g_y = g_y, inputs.pitch = state.pitch, inputs.roll = state.roll;
      StepTrackSoil(veh, *terrain.track_soil, sc.mismatch, variation, inputs, dt, body);
      u[0] = body[0], u[1] = body[2], u[2] = body[1];
      const double crossed[2] = {(u[0] - 0.5 * c * u[2]) * dt, (u[0] + 0.5 * c * u[2]) * dt};
      variation.Advance(crossed, sc.mismatch.track_soil_correlation_m, &soil_rng, &soil_unit);
    } else {
      ipd::SlipVelocities(v_n, w_n, g_x, g_y, terrain.ipd.alpha.data(), u);
      // Stochastic slip: Gauss-Markov with low-frequency density q = 2 sd^2 tau.
      for (int i = 0; i < 3; ++i) {
        const double sd = std::sqrt(terrain.ipd.q_density[i] / (2.0 * kSlipNoiseTauS));
        noise[i] = noise[i] * decay + sd * std::sqrt(1.0 - decay * decay) * unit(rng);
        u[i] += noise[i];
      }
      u[0] += v_n;
      u[2] += w_n;
    }

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
