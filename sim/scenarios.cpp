#include "sim/scenarios.h"

#include <cstdio>
#include <random>
#include <stdexcept>

namespace slipgraph {
namespace sim {
namespace {

// A terrain with exactly the nominal coefficients the user believes (hidden-effect logs: the
// only model error is the hidden effect).
TerrainType NominalTerrain(const Vehicle& vehicle, bool soft) {
  return {soft ? "nominal_soft" : "nominal", vehicle.tire, vehicle.rolling, soft};
}

uint64_t RunSeed(uint64_t seed, uint64_t run) { return seed * 1000003ULL + run; }

// One Ward & Iagnemma style run: rest, drive (with a gentle turn), get held back with the wheels
// spinning, released, drive on, stop, rest.
Scenario Ward21Run(int run, uint64_t seed) {
  std::mt19937_64 rng(RunSeed(seed, run));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  static const char* const kTerrains[] = {"mulch", "gravel", "mud", "grass"};
  Scenario sc;
  char name[32];
  std::snprintf(name, sizeof(name), "ward21/%02d", run);
  sc.name = name;
  sc.vehicle = LagrVehicle();
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

Scenario Fig5(uint64_t) {
  Scenario sc;
  sc.name = "fig5";
  sc.vehicle = LagrVehicle();
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
  sc.commands = {{10.0, 0.5, 0.0},  {8.0, 1.2, 0.0},  {6.0, 1.2, 0.5},  {8.0, 0.8, 0.0},
                 {6.0, 0.8, -0.6},  {12.0, 1.0, 0.0}, {5.0, 0.3, 0.0},  {10.0, 1.4, 0.0},
                 {6.0, 0.6, 0.4},   {8.0, 1.0, 0.0},  {4.0, 0.0, 0.0}};
  if (effect != "none") {
    const EffectInfo* info = FindEffect(effect);
    if (info == nullptr) throw std::invalid_argument("unknown effect '" + effect + "'");
    sc.effects[effect] = info->default_value;
  }
  return sc;
}

}  // namespace

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
  v.tire = {0.55, 15.0, 0.05};
  v.rolling = {0.05, 20.0, 0.015};
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
  } else if (name == "fig5") {
    runs.push_back({"", Fig5(seed), seed});
  } else if (name == "hidden") {
    runs.push_back({"none", HiddenEffect("none"), seed});
    for (const EffectInfo& effect : EffectCatalogue()) {
      runs.push_back({effect.name, HiddenEffect(effect.name), seed});
    }
  } else if (name.rfind("hidden/", 0) == 0) {
    runs.push_back({"", HiddenEffect(name.substr(7)), seed});
  } else {
    throw std::invalid_argument("unknown scenario '" + name + "'; " + ScenarioHelp());
  }
  return runs;
}

std::string ScenarioHelp() {
  return "scenarios: ward21, ward21/NN (01..21), fig5, hidden, hidden/EFFECT, hidden/none";
}

}  // namespace sim
}  // namespace slipgraph
