#include "sim/rocker_bogie_sim.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "factors/slip_ratio.h"
#include "sim/command_schedule.h"
#include "sim/random.h"
#include "sim/sensor_models.h"

namespace slipgraph {
namespace sim {
namespace {

constexpr double kSoftPatchLengthM = 0.6;

double RaisedCosine(double u) {
  return (u <= 0.0 || u >= 1.0) ? 0.0 : 0.5 * (1.0 - std::cos(2.0 * M_PI * u));
}

// How soft the ground is at x: 0 outside the soft patches, 1 at their centres.
double Softness(const RockerSpec& spec, double x_m) {
  if (x_m <= 0.0) return 0.0;
  return RaisedCosine(std::fmod(x_m, spec.soft_patch_every_m) / kSoftPatchLengthM);
}

// Sinkage of the front wheel's rut at x on one side.
double Sinkage(const RockerSpec& spec, double x_m, bool left) {
  const double soft = Softness(spec, x_m);
  return spec.base_sinkage_m + spec.soft_sinkage_m * soft +
         (left ? spec.left_extra_sinkage_m * soft : 0.0);
}

// Sinkage of wheel w (0 rear, 1 middle, 2 front) at x: the following wheels deepen the rut.
double WheelSinkage(const RockerSpec& spec, double x_m, bool left, int w) {
  const double deepening =
      w == 0 ? spec.rear_extra_sinkage : (w == 1 ? spec.middle_extra_sinkage : 0.0);
  return Sinkage(spec, x_m, left) * (1.0 + deepening);
}

// The course's hills as an elevation along the path, z(x) = integral of tan(grade): a table at
// 1 mm, interpolated (both sides ride the same hills).
class HillElevation {
 public:
  HillElevation(const Course& course, double length_m) : course_(course) {
    z_.push_back(0.0);
    if (course.hills.empty()) return;
    const size_t n = static_cast<size_t>(std::ceil(length_m / kStepM)) + 1;
    for (size_t i = 1; i < n; ++i) {
      const double slope0 = std::tan(course.GradeRad((i - 1) * kStepM));
      const double slope1 = std::tan(course.GradeRad(i * kStepM));
      z_.push_back(z_.back() + 0.5 * (slope0 + slope1) * kStepM);
    }
  }
  double At(double x_m) const {
    if (z_.size() < 2 || x_m <= 0.0) return z_.front();
    const double u = x_m / kStepM;
    const size_t i = std::min(static_cast<size_t>(u), z_.size() - 2);
    const double f = std::min(1.0, u - i);
    return (1.0 - f) * z_[i] + f * z_[i + 1];
  }
  double Slope(double x_m) const { return std::tan(course_.GradeRad(x_m)); }

 private:
  static constexpr double kStepM = 0.001;
  const Course& course_;
  std::vector<double> z_;
};

}  // namespace

SimResult SimulateRockerBogie(const Scenario& sc, uint64_t seed) {
  std::mt19937_64 rng(seed);
  UnitNormal unit;
  const RockerSpec& spec = sc.rocker;
  SimResult result;
  DriveLog& log = result.log;
  log.vehicle = sc.vehicle;
  log.present_files = {"vehicle.yaml", "imu.csv",          "wheels.csv",
                       "truth.csv",    "articulation.csv", "range.csv"};
  const Vehicle& veh = sc.vehicle;
  const double r_nominal = veh.wheel_radius_m;
  const double r_true = r_nominal * (1.0 + EffectValue(sc.effects, "wheel_radius_error"));
  result.true_wheel_radius_m = r_true;
  const double axle = veh.axle_spacing_m;
  const double patch = r_true / spec.contact_divisor;
  const double dt = sc.sim_step_s;
  const double duration = sc.duration_s();
  double top_speed = 0.0;
  for (const CommandSegment& c : sc.commands) top_speed = std::max(top_speed, c.v_mps);
  const double course_length = top_speed * duration + 2.0 * axle + 2.0;
  const TerrainProfile left = MakeTerrainProfile(spec.roughness_rms_m, course_length, seed ^ 0x1);
  const TerrainProfile right = MakeTerrainProfile(spec.roughness_rms_m, course_length, seed ^ 0x2);
  const TerrainProfile* sides[2] = {&left, &right};
  result.profiles = {left, right};
  const HillElevation hills(sc.course, course_length);
  // Terrain elevation (profile and hills) at x, and the surface a wheel rides on (y - s).
  const auto terrain = [&](int side, double x) { return sides[side]->Elevation(x) + hills.At(x); };
  const auto ride = [&](int side, double x, int w) {
    return sides[side]->WheelElevation(x, patch) + hills.At(x) -
           WheelSinkage(spec, x, side == 0, w);
  };

  SensorSimulator sensors(sc.sensors, sc.effects, 6, dt, &rng, &log);
  result.imu_errors = sensors.imu_errors();
  const int64_t truth_period = std::llround(1.0 / (sc.sensors.truth_rate_hz * dt));
  const int64_t cycle_period = std::llround(1.0 / (spec.cycle_rate_hz * dt));
  const int64_t steps = std::llround(duration / dt);
  const double steps_per_s = std::round(1.0 / dt);

  CommandSchedule commands(sc);
  KinematicState state;
  double x_rear = 0.0;  // rear wheel contact, along the straight path
  double slip = spec.slip_mean;
  // The correlated slip's variation (wilcoxm), drawn from its stationary spread at the start.
  double slip_state = 0.0, x_last_cycle = -1e9;
  for (int64_t k = 0; k <= steps; ++k) {
    const double t = k / steps_per_s;
    commands.Step(t, dt);
    if (k % cycle_period == 0) {
      double variation = unit(rng);
      if (spec.slip_correlation_m > 0.0) {  // Gauss-Markov in the distance since the last cycle
        variation = slip_state = GaussMarkovStep(slip_state, 1.0, spec.slip_correlation_m,
                                                 x_rear - x_last_cycle, variation);
        x_last_cycle = x_rear;
      }
      slip = std::clamp(spec.slip_mean + spec.slip_per_slope * hills.Slope(x_rear + axle) +
                            spec.slip_sd * variation +
                            spec.soft_extra_slip * Softness(spec, x_rear + axle),
                        0.0, 0.9);
    }
    const double omega = commands.v_mps() / r_nominal;
    const double v = r_true * omega * (1.0 - slip);
    // Wheel contact elevations, [side][rear, middle, front].
    double z[2][3];
    for (int side = 0; side < 2; ++side) {
      for (int w = 0; w < 3; ++w) z[side][w] = ride(side, x_rear + w * axle, w);
    }
    state.t = t;
    state.x = x_rear;
    state.z = 0.5 * (z[0][0] + z[1][0]);
    state.pitch = -std::atan2(0.5 * (z[0][2] + z[1][2]) - state.z, 2.0 * axle);
    state.roll = std::atan2(z[0][1] - z[1][1], veh.track_width_m);  // right side down > 0
    state.v_bx = v;
    state.yaw_rate = 0.0;
    for (int w = 0; w < 6; ++w) state.omega_radps[w] = omega;
    state.command_v_mps = commands.v_mps();
    sensors.Observe(state, k);

    if (k % cycle_period == 0) {
      for (int side = 0; side < 2; ++side) {
        const Side label = side == 0 ? Side::kLeft : Side::kRight;
        log.articulation.push_back({t, label,
                                    z[side][1] - z[side][0] + spec.articulation_sd_m * unit(rng),
                                    z[side][2] - z[side][0] + spec.articulation_sd_m * unit(rng)});
      }
      for (int side = 0; side < 2; ++side) {
        const Side label = side == 0 ? Side::kLeft : Side::kRight;
        for (int i = 0; i < spec.range_points; ++i) {
          const double d = 2.0 * axle + spec.range_first_m + i * spec.range_spacing_m;
          log.range.push_back({t, label, d,
                               terrain(side, x_rear + d) - z[side][0] +
                                   d * std::tan(spec.range_pitch_error_rad) +
                                   spec.range_sd_m * unit(rng)});
        }
      }
    }
    if (k % truth_period == 0) {
      TruthSample truth;
      truth.t = t;
      truth.x = state.x, truth.y = 0.0, truth.z = state.z;
      truth.roll = state.roll, truth.pitch = state.pitch, truth.yaw = 0.0;
      truth.vx = v, truth.vy = 0.0, truth.yaw_rate = 0.0;
      truth.a_dist = kMissing;
      truth.immobilized = 0.0;
      truth.slip.fill(kMissing);
      truth.sinkage.fill(kMissing);
      // Wheel order fl, ml, rl, fr, mr, rr: front = 2, middle = 1, rear = 0 along the path.
      for (int side = 0; side < 2; ++side) {
        for (int w = 0; w < 3; ++w) {
          const int column = side * 3 + (2 - w);
          truth.slip[column] = SlipRatio(r_true * omega, v);
          truth.sinkage[column] = WheelSinkage(spec, x_rear + w * axle, side == 0, w);
        }
      }
      log.truth.push_back(truth);
    }
    x_rear += v * dt;
    for (int w = 0; w < 6; ++w) state.wheel_angle_rad[w] += omega * dt;
  }
  return result;
}

}  // namespace sim
}  // namespace slipgraph
