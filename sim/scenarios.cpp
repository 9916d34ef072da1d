#include "sim/scenarios.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "sim/random.h"

namespace slipgraph {
namespace sim {
namespace {

// A terrain with exactly the nominal coefficients the user believes (hidden-effect logs: the
// only model error is the hidden effect).
TerrainType NominalTerrain(const Vehicle& vehicle, bool soft) {
  return {soft ? "nominal_soft" : "nominal",
          vehicle.tire,
          vehicle.rolling,
          soft,
          IpdSlip{},
          std::nullopt,
          std::nullopt};
}

uint64_t RunSeed(uint64_t seed, uint64_t run) { return seed * 1000003ULL + run; }

// The laws of the soils a user fitted one law over (LagrVehicle's is their mean): written to
// vehicle.yaml as `law_samples`, their spread is what the user knows about the law's error.
void SetLawSamples(const std::vector<std::string>& terrains, Vehicle* vehicle) {
  vehicle->law_samples.clear();
  for (const std::string& name : terrains) {
    const TerrainType& t = FindTerrain(name);
    vehicle->law_samples.push_back({t.tire, t.rolling});
  }
}

// One Ward & Iagnemma style run: rest, drive (with a gentle turn), get held back with the wheels
// spinning, released, drive on, stop, rest.
Scenario Ward21Run(int run, uint64_t seed) {
  std::mt19937_64 rng(RunSeed(seed, run));
  UniformReal u(0.0, 1.0);
  static const char* const kTerrains[] = {"mulch", "gravel", "mud", "grass"};
  Scenario sc;
  char name[32];
  std::snprintf(name, sizeof(name), "ward21/%02d", run);
  sc.name = name;
  sc.vehicle = LagrVehicle();
  // The user's law is the mean over these soils (LagrVehicle); vehicle.yaml states them.
  SetLawSamples({kTerrains, kTerrains + 4}, &sc.vehicle);
  const std::string first = kTerrains[(run - 1) % 4];
  const std::string second = kTerrains[(run + 1) % 4];
  const double speed = 0.1 + 0.9 * u(rng);
  const double distance = 4.5 + 2.5 * u(rng);  // ~120 m over 21 runs
  sc.course.patches = {{0.0, FindTerrain(first)}, {0.5 * distance, FindTerrain(second)}};
  if (u(rng) < 0.5) {
    sc.course.hills.push_back(
        {1.0 + u(rng), 2.0 + 2.0 * u(rng), 0.08 * (u(rng) - 0.5), 0.06 * (u(rng) - 0.5)});
  }
  const double drive_time = distance / speed;
  const double turn = 0.3 * (u(rng) - 0.5);
  sc.rest_start_s = 3.0;
  sc.commands = {{0.35 * drive_time, speed, 0.0},
                 {0.30 * drive_time, speed, turn},
                 {0.35 * drive_time, speed, 0.0},
                 {3.0, 0.0, 0.0}};
  if (run <= 20) {  // 20 hold-back events over the 21 runs
    const double hold_start = sc.rest_start_s + 2.0 + (0.3 + 0.4 * u(rng)) * drive_time;
    sc.holdbacks.push_back({hold_start, hold_start + 3.0 + 2.0 * u(rng)});
    sc.commands[2].duration_s += sc.holdbacks.back().t_end_s - hold_start;
  }
  return sc;
}

// The user's vehicle.yaml carries the grass coefficients here: a robot calibrated on the grass
// it is tested on (the single-terrain experiment of the figure), unlike ward21's mean fit.
Scenario Fig5(uint64_t) {
  Scenario sc;
  sc.name = "fig5";
  sc.vehicle = LagrVehicle();
  sc.vehicle.tire = FindTerrain("grass").tire;
  sc.vehicle.rolling = FindTerrain("grass").rolling;
  sc.course.patches = {{0.0, FindTerrain("grass")}};
  sc.rest_start_s = 3.0;
  sc.commands = {{14.0, 1.0, 0.0}, {3.0, 0.0, 0.0}};
  sc.holdbacks = {{10.0, 14.0}};
  return sc;
}

// A drive rich enough to expose every catalogue effect: several speeds, accelerations, turns
// both ways, a hill with cross slope, a soft patch; nominal tire coefficients throughout.
Scenario HiddenEffect(const std::string& effect) {
  Scenario sc;
  sc.name = "hidden/" + effect;
  sc.vehicle = LagrVehicle();
  sc.course.patches = {{0.0, NominalTerrain(sc.vehicle, false)},
                       {20.0, NominalTerrain(sc.vehicle, true)},
                       {35.0, NominalTerrain(sc.vehicle, false)}};
  sc.course.hills = {{45.0, 12.0, 0.12, 0.04}, {65.0, 10.0, -0.10, -0.03}};
  sc.rest_start_s = 3.0;
  sc.commands = {{10.0, 0.5, 0.0}, {8.0, 1.2, 0.0},  {6.0, 1.2, 0.5}, {8.0, 0.8, 0.0},
                 {6.0, 0.8, -0.6}, {12.0, 1.0, 0.0}, {5.0, 0.3, 0.0}, {10.0, 1.4, 0.0},
                 {6.0, 0.6, 0.4},  {8.0, 1.0, 0.0},  {4.0, 0.0, 0.0}};
  if (effect != "none") {
    const EffectInfo* info = FindEffect(effect);
    if (info == nullptr) throw std::invalid_argument("unknown effect '" + effect + "'");
    sc.effects[effect] = info->default_value;
  }
  return sc;
}

// Rogers-Marcovitz et al. Sec. III: 35 minutes of varied driving (up to 1.7 m/s and 3 rad/s)
// over soft dirt, asphalt, loose rock and grass, with terrain boundaries and slopes.
Scenario Ipd35(uint64_t seed) {
  std::mt19937_64 rng(RunSeed(seed, 35));
  UniformReal u(0.0, 1.0);
  Scenario sc;
  sc.name = "ipd35";
  sc.vehicle = TrackedVehicle();
  sc.sim_step_s = 0.001;
  sc.actuation.accel_limit_mps2 = 1.5;
  sc.actuation.yaw_accel_limit_radps2 = 4.0;
  sc.sensors.gps_rate_hz = 0.0;  // post-processed GNSS/INS pose instead
  sc.sensors.pose_rate_hz = 10.0;
  sc.sensors.encoder_counts_per_rev = 2048;
  sc.sensors.sd_accel_mps2 = 0.01;  // tactical-grade IMU
  sc.sensors.sd_gyro_radps = 0.0005;
  sc.sensors.accel_offset_max_mps2 = 0.02;
  sc.sensors.gyro_offset_max_radps = 0.001;
  sc.sensors.accel_bias_sd_mps2 = 0.002;
  sc.sensors.gyro_bias_sd_radps = 0.0002;
  sc.sensors.pose_sd_xy_m = 0.02;
  sc.sensors.pose_sd_yaw_rad = 0.005;
  static const char* const kTerrains[] = {"soft_dirt", "asphalt", "loose_rock", "grass"};
  // Terrain patches of 150-350 m, cycling, over the ~2 km driven.
  double s = 0.0;
  for (int i = 0; s < 4000.0; ++i) {
    sc.course.patches.push_back({s, FindTerrain(kTerrains[i % 4])});
    s += 150.0 + 200.0 * u(rng);
  }
  for (double h = 20.0; h < 4000.0; h += 25.0 + 30.0 * u(rng)) {
    sc.course.hills.push_back(
        {h, 8.0 + 12.0 * u(rng), 0.24 * (u(rng) - 0.5), 0.16 * (u(rng) - 0.5)});
  }
  sc.rest_start_s = 3.0;
  double total = sc.rest_start_s;
  while (total < 35.0 * 60.0) {
    CommandSegment segment;
    segment.duration_s = 2.0 + 4.0 * u(rng);
    segment.v_mps = 0.2 + 1.5 * u(rng);
    // Track speeds stay within 1.7 m/s: |v| + c/2 |w| <= 1.7 + margin for sharp turns.
    const double max_w = std::min(3.0, (2.0 - segment.v_mps) / (0.5 * sc.vehicle.track_width_m));
    segment.yaw_rate_radps = max_w * (2.0 * u(rng) - 1.0) * (u(rng) < 0.2 ? 0.1 : 1.0);
    sc.commands.push_back(segment);
    total += segment.duration_s;
  }
  sc.commands.push_back({2.0, 0.0, 0.0});
  return sc;
}

// Wilcox Fig. 4: the rover drives 5 m straight at a rim speed of 6.25 cm/s with 20 % slip (about
// 5 cm of advance per 1 Hz cycle) over terrain of the given RMS roughness.
Scenario WilcoxRun(double roughness_m, double left_extra_sinkage_m, const std::string& name) {
  Scenario sc;
  sc.name = name;
  sc.vehicle = RockerVehicle();
  sc.sim_step_s = 0.01;
  sc.course.patches = {{0.0, NominalTerrain(sc.vehicle, true)}};
  sc.rest_start_s = 3.0;
  sc.commands = {{100.0, 0.0625, 0.0}};
  sc.actuation.accel_limit_mps2 = 0.1;
  sc.rocker.roughness_rms_m = roughness_m;
  sc.rocker.left_extra_sinkage_m = left_extra_sinkage_m;
  SensorSpec& s = sc.sensors;
  s.imu_rate_hz = 50.0, s.wheel_rate_hz = 10.0, s.attitude_rate_hz = 10.0;
  s.truth_rate_hz = 10.0, s.command_rate_hz = 1.0, s.gps_rate_hz = 0.0;
  s.encoder_counts_per_rev = 0;  // geared wheel speed from motor encoders: no coarse quanta
  s.sd_omega_radps = 0.002;
  return sc;
}

// A hill up and down under the rover, slip rising with the slope (Wilcox Sec. 5): 20 % on the
// level, +1 per unit of slope (peak grade 0.2 rad: 40 % up, 0 % down).
Scenario WilcoxSlopeRun(double roughness_m, const std::string& name) {
  Scenario sc = WilcoxRun(roughness_m, 0.0, name);
  sc.course.hills = {{0.5, 2.0, 0.2, 0.0}, {2.5, 2.0, -0.2, 0.0}};
  sc.rocker.slip_per_slope = 1.0;
  return sc;
}

// The mismatch suites (docs/mismatch.md): the scenario with truth the estimators do not contain.
// Soils per patch of 10-40 m from the peaked law's ranges (sim/peaked_tire.h), never eq. (8)'s;
// tire relaxation and load-dependent rolling radius; an AHRS with 0.5 deg noise and a 0.3 deg
// slowly varying error; chassis vibration; GNSS velocity averaged over each fix's interval. The
// user's vehicle.yaml keeps one nominal law and lists no soils, as for a new robot. The ranges
// were fixed before any estimator ran on these suites. Its own random stream: the matched
// scenario's draws are unchanged.
void ApplyMismatch(uint64_t stream_seed, double course_m, Scenario* sc) {
  std::mt19937_64 rng(stream_seed ^ 0x6d69736d61746368ULL);
  UniformReal u(0.0, 1.0);
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
  const size_t slash = sc->name.find('/');  // ward21/03 -> ward21m/03, fig5 -> fig5m
  sc->name.insert(slash == std::string::npos ? sc->name.size() : slash, "m");
  sc->vehicle.law_samples.clear();
  const bool soft_course = std::any_of(sc->course.patches.begin(), sc->course.patches.end(),
                                       [](const TerrainPatch& p) { return p.terrain.soft; });
  std::vector<TerrainPatch> patches;
  int index = 0;
  // The first patch began before the drive: it ends 0-40 m in.
  for (double start = 0.0, end = in(0.0, 40.0); start < course_m + 40.0;
       start = end, end += in(10.0, 40.0)) {
    PeakedSoil soil;
    soil.peak_mu = in(0.30, 0.90);
    soil.stiffness_b = in(4.0, 14.0);
    soil.shape_c = in(1.3, 1.8);
    soil.curvature_e = in(-0.5, 0.3);
    soil.roll_c0 = in(0.015, 0.10);
    soil.roll_c1_spm = in(0.0, 0.04);
    TerrainType terrain;
    terrain.name = "peaked_" + std::to_string(++index);
    terrain.tire = sc->vehicle.tire;  // unused: the peaked law acts
    terrain.rolling = sc->vehicle.rolling;
    // Soft ground (sinkage_resistance acts there) where the rolling resistance is high.
    terrain.soft = soft_course && soil.roll_c0 > 0.0575;
    terrain.peaked = soil;
    patches.push_back({start, terrain});
  }
  sc->course.patches = patches;
  sc->mismatch.relaxation_length_m = in(0.1, 0.3);
  sc->mismatch.radius_load_sensitivity = in(0.0, 0.05);
  SensorSpec& sensors = sc->sensors;
  sensors.attitude_sd_rad = 0.5 * M_PI / 180.0;
  sensors.mismatch.attitude_error_sd_rad = 0.3 * M_PI / 180.0;
  sensors.mismatch.attitude_error_tau_s = in(20.0, 60.0);
  sensors.mismatch.vibration_sd_mps2_per_mps = 0.25;
  sensors.mismatch.vibration_hz = in(10.0, 15.0);
  sensors.mismatch.vibration_damping = 0.05;
  sensors.mismatch.gps_velocity_interval_mean = true;
}

// ipd35m (docs/mismatch.md): ipd35's drive, course and sensors with the tracks' slip from a
// track-soil model (sim/track_soil.h) instead of the 13-parameter slip model IPD identifies; each
// patch's soil drawn from ranges fixed before any estimator ran on the suite, the soil varying
// under each track along the path. Its own random stream: ipd35's draws are unchanged.
Scenario Ipd35Mismatched(uint64_t seed) {
  Scenario sc = Ipd35(seed);
  sc.name = "ipd35m";
  std::mt19937_64 rng(RunSeed(seed, 35) ^ 0x6970643335736f6cULL);
  UniformReal u(0.0, 1.0);
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
  int index = 0;
  for (TerrainPatch& patch : sc.course.patches) {
    TrackSoil soil;
    soil.cohesion_pa = in(0.0, 6000.0);
    soil.friction_angle_rad = in(20.0, 38.0) * M_PI / 180.0;
    soil.shear_modulus_m = in(0.01, 0.04);
    soil.roll_c0 = in(0.02, 0.10);
    soil.roll_c1_spm = in(0.0, 0.03);
    patch.terrain.name = "track_soil_" + std::to_string(++index);
    patch.terrain.ipd = IpdSlip{};  // unused: the track-soil model acts
    patch.terrain.soft = soil.roll_c0 > 0.06;
    patch.terrain.track_soil = soil;
  }
  sc.mismatch.tracks = {0.7, 0.2};
  sc.mismatch.track_soil_variation_sd = in(0.1, 0.3);
  sc.mismatch.track_soil_correlation_m = in(1.0, 5.0);
  return sc;
}

// wilcoxm (docs/mismatch.md): a wilcox run whose truth breaks the estimators' assumptions: slip
// correlated over distance around a mean that is not the prior's, more slip on soft ground, the
// following wheels deepening the front's rut, a wider or narrower wheel contact, a ranging
// sensor pitched off its calibration. Ranges fixed before any estimator ran on the suite; its own
// random stream (wilcox's draws are unchanged).
Scenario WilcoxMismatched(Scenario sc, uint64_t stream_seed) {
  std::mt19937_64 rng(stream_seed ^ 0x77696c636f786dULL);
  UniformReal u(0.0, 1.0);
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
  const size_t slash = sc.name.find('/');  // wilcox/r1cm_run01 -> wilcoxm/r1cm_run01
  sc.name.insert(slash == std::string::npos ? sc.name.size() : slash, "m");
  RockerSpec& r = sc.rocker;
  r.slip_mean = in(0.15, 0.30);
  r.slip_sd = in(0.03, 0.06);
  r.slip_correlation_m = in(0.2, 1.0);
  r.soft_extra_slip = in(0.05, 0.15);
  r.middle_extra_sinkage = in(0.0, 0.3);
  r.rear_extra_sinkage = r.middle_extra_sinkage + in(0.0, 0.3);
  r.contact_divisor = in(2.0, 5.0);
  r.range_pitch_error_rad = (u(rng) < 0.5 ? -1.0 : 1.0) * in(0.0, 0.3) * M_PI / 180.0;
  return sc;
}

// The path length a scenario covers at its commanded speeds (the mismatch patches cover it).
double CommandedDistanceM(const Scenario& sc) {
  double distance = 0.0;
  for (const CommandSegment& c : sc.commands) distance += std::abs(c.v_mps) * c.duration_s;
  return distance;
}

Scenario Mismatched(Scenario sc, uint64_t stream_seed) {
  ApplyMismatch(stream_seed, CommandedDistanceM(sc), &sc);
  return sc;
}

const double kWilcoxRoughnessCm[] = {0.25, 0.5, 1.0, 2.0, 4.0};
constexpr int kWilcoxRunsPerRoughness = 8;

}  // namespace

Vehicle RockerVehicle() {
  Vehicle v;
  v.name = "rover";
  v.type = VehicleType::kRockerBogie6;
  v.mass_kg = 11.5;
  v.yaw_inertia_kgm2 = 0.5;
  v.wheel_radius_m = 0.065;
  v.track_width_m = 0.45;
  v.cg_height_m = 0.2;
  v.axle_spacing_m = 0.24;
  v.tire = {0.6, 15.0, 0.05};
  v.rolling = {0.08, 20.0, 0.05};
  v.sensors = {0.02, 0.002, 0.005, 0.5, 0.1};
  return v;
}

Vehicle TrackedVehicle() {
  Vehicle v;
  v.name = "tracked";
  v.type = VehicleType::kSkidSteer;
  v.mass_kg = 300.0;
  v.yaw_inertia_kgm2 = 40.0;
  v.wheel_radius_m = 0.15;
  v.track_width_m = 0.8;
  v.cg_height_m = 0.35;
  v.tire = {0.6, 15.0, 0.05};
  v.rolling = {0.05, 20.0, 0.015};
  v.sensors = {0.01, 0.0005, 0.03, 0.02, 0.05};
  return v;
}

Vehicle LagrVehicle() {
  Vehicle v;
  v.name = "lagr";
  v.type = VehicleType::kDiffDriveCastor;
  v.mass_kg = 117.0;
  v.yaw_inertia_kgm2 = 15.0;
  v.wheel_radius_m = 0.25;
  v.track_width_m = 0.55;
  v.cg_to_front_m = 0.35;
  v.cg_to_rear_m = 0.55;
  v.cg_height_m = 0.30;
  // The user's tire and rolling coefficients: the mean of the four ward21 terrains (mulch,
  // gravel, mud, grass), as a fit over all of them would give; each terrain differs from it by
  // 10-35 % per coefficient (compare Ward & Iagnemma's +-20 % sensitivity study).
  v.tire = {0.475, 13.25, 0.068};
  v.rolling = {0.0625, 16.25, 0.02};
  v.sensors = {0.05, 0.005, 0.05, 0.5, 0.1};
  return v;
}

std::vector<ScenarioRun> ExpandScenario(const std::string& name, uint64_t seed) {
  std::vector<ScenarioRun> runs;
  if (name == "ward21") {
    for (int run = 1; run <= 21; ++run) {
      char dir[16];
      std::snprintf(dir, sizeof(dir), "run_%02d", run);
      runs.push_back({dir, Ward21Run(run, seed), RunSeed(seed, run)});
    }
  } else if (name.rfind("ward21/", 0) == 0) {
    const int run = std::atoi(name.c_str() + 7);
    if (run < 1 || run > 21) throw std::invalid_argument("ward21 runs are 01..21: '" + name + "'");
    runs.push_back({"", Ward21Run(run, seed), RunSeed(seed, run)});
  } else if (name == "ward21m") {
    for (int run = 1; run <= 21; ++run) {
      char dir[16];
      std::snprintf(dir, sizeof(dir), "run_%02d", run);
      runs.push_back(
          {dir, Mismatched(Ward21Run(run, seed), RunSeed(seed, run)), RunSeed(seed, run)});
    }
  } else if (name.rfind("ward21m/", 0) == 0) {
    const int run = std::atoi(name.c_str() + 8);
    if (run < 1 || run > 21) throw std::invalid_argument("ward21m runs are 01..21: '" + name + "'");
    runs.push_back({"", Mismatched(Ward21Run(run, seed), RunSeed(seed, run)), RunSeed(seed, run)});
  } else if (name == "fig5") {
    runs.push_back({"", Fig5(seed), seed});
  } else if (name == "fig5m") {
    Scenario sc = Fig5(seed);
    sc.vehicle = LagrVehicle();  // no calibration on this ground: the nominal law
    runs.push_back({"", Mismatched(sc, seed), seed});
  } else if (name == "ipd35") {
    runs.push_back({"", Ipd35(seed), RunSeed(seed, 35)});
  } else if (name == "ipd35m") {
    runs.push_back({"", Ipd35Mismatched(seed), RunSeed(seed, 35)});
  } else if (name == "wilcox" || name == "wilcoxm") {
    for (double roughness_cm : kWilcoxRoughnessCm) {
      for (int run = 1; run <= kWilcoxRunsPerRoughness; ++run) {
        char dir[48];
        std::snprintf(dir, sizeof(dir), "r%gcm_run%02d", roughness_cm, run);
        const uint64_t run_seed =
            RunSeed(seed, static_cast<uint64_t>(roughness_cm * 100) * 100 + run);
        Scenario sc = WilcoxRun(roughness_cm / 100.0, 0.0, std::string("wilcox/") + dir);
        if (name == "wilcoxm") sc = WilcoxMismatched(sc, run_seed);
        runs.push_back({dir, sc, run_seed});
      }
    }
  } else if (name == "wilcox_lr") {
    // Left/right consistency: 2 cm roughness, half the runs with 1 cm more sinkage on the left
    // in the soft patches (the same-ruts assumption then fails on one side).
    for (int run = 1; run <= 4; ++run) {
      for (bool asymmetric : {false, true}) {
        char dir[48];
        std::snprintf(dir, sizeof(dir), "%s_run%02d", asymmetric ? "asym" : "sym", run);
        runs.push_back({dir,
                        WilcoxRun(0.02, asymmetric ? 0.01 : 0.0, std::string("wilcox_lr/") + dir),
                        RunSeed(seed, 900 + run)});
      }
    }
  } else if (name == "wilcox_slope") {
    for (double roughness_cm : {1.0, 2.0}) {
      for (int run = 1; run <= 6; ++run) {
        char dir[48];
        std::snprintf(dir, sizeof(dir), "r%gcm_run%02d", roughness_cm, run);
        runs.push_back({dir,
                        WilcoxSlopeRun(roughness_cm / 100.0, std::string("wilcox_slope/") + dir),
                        RunSeed(seed, 5000 + static_cast<uint64_t>(roughness_cm) * 100 + run)});
      }
    }
  } else if (name.rfind("wilcox/", 0) == 0) {
    // wilcox/<roughness cm>, e.g. wilcox/1: one run of the suite.
    const double roughness_cm = std::atof(name.c_str() + 7);
    if (!(roughness_cm > 0.0))
      throw std::invalid_argument("wilcox/<roughness in cm>: '" + name + "'");
    runs.push_back({"", WilcoxRun(roughness_cm / 100.0, 0.0, name), RunSeed(seed, 777)});
  } else if (name == "hidden") {
    runs.push_back({"none", HiddenEffect("none"), seed});
    for (const EffectInfo& effect : EffectCatalogue()) {
      runs.push_back({effect.name, HiddenEffect(effect.name), seed});
    }
  } else if (name.rfind("hidden/", 0) == 0) {
    runs.push_back({"", HiddenEffect(name.substr(7)), seed});
  } else if (name == "hiddenm") {
    // GNSS velocity is averaged in every mismatch log: that effect is not hidden there.
    runs.push_back({"none", Mismatched(HiddenEffect("none"), seed), seed});
    for (const EffectInfo& effect : EffectCatalogue()) {
      if (effect.name == "gps_velocity_averaging") continue;
      runs.push_back({effect.name, Mismatched(HiddenEffect(effect.name), seed), seed});
    }
  } else if (name.rfind("hiddenm/", 0) == 0) {
    runs.push_back({"", Mismatched(HiddenEffect(name.substr(8)), seed), seed});
  } else {
    throw std::invalid_argument("unknown scenario '" + name + "'; " + ScenarioHelp());
  }
  return runs;
}

std::string ScenarioHelp() {
  return "scenarios: ward21, ward21/NN (01..21), fig5, ipd35, wilcox, wilcox/ROUGHNESS_CM, "
         "wilcox_lr, wilcox_slope, hidden, hidden/EFFECT, hidden/none; mismatch suites (truth "
         "the model lacks): ward21m, ward21m/NN, fig5m, hiddenm, hiddenm/EFFECT, ipd35m, wilcoxm";
}

}  // namespace sim
}  // namespace slipgraph
