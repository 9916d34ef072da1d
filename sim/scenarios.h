// Named scenarios and suites for `slipgraph simulate --scenario NAME`:
//   ward21            21 LAGR runs (Ward & Iagnemma Sec. III): ~120 m over mulch, gravel, mud
//                     and grass at 0.1-1 m/s with 20 hold-back events; a suite (run_01..run_21)
//   ward21/NN         one run of it (NN = 01..21)
//   fig5              the paper's Fig. 5: 1 m/s on grass, then held back (325 N) for 4 s
//   ipd35             tracked skid-steer robot, 35 min over soft dirt, asphalt, loose rock and
//                     grass with terrain boundaries (Rogers-Marcovitz et al. Sec. III)
//   wilcox            articulated rover, roughness 0.25-4 cm RMS at 20 % slip, 8 runs each
//                     (Wilcox Fig. 4); wilcox/R: one run at R cm
//   wilcox_lr         4 runs with equal sinkage on both sides, 4 with more on the left
//   wilcox_slope      6 runs each at 1 and 2 cm over a hill up and down, slip 20 % + the slope
//   hidden            one log per catalogue effect with only that effect on, plus `none`
//   hidden/EFFECT     one of them (hidden/none: no effect)
//   ward21m, ward21m/NN, fig5m, hiddenm, hiddenm/EFFECT
//                     the mismatch suites: the same drives with truth the estimators do not
//                     contain (peaked traction law, soils per 10-40 m patch, AHRS error,
//                     vibration, averaged GNSS velocity; docs/mismatch.md)
//   ipd35m            ipd35's drive with the tracks' slip from a track-soil model (shear
//                     against soils drawn per patch) instead of the 13-parameter slip model
//   wilcoxm           the wilcox runs with slip correlated over distance around another mean,
//                     more slip on soft ground, deeper ruts under the following wheels, a
//                     tilted ranging sensor
// Every scenario is a pure function of (name, seed): the same inputs give the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/scenario.h"

namespace slipgraph {
namespace sim {

// The LAGR robot as its user believes it to be (vehicle.yaml of the simulated logs).
Vehicle LagrVehicle();
// The 6-wheel rocker-bogie rover of the wilcox suites (Sojourner-like).
Vehicle RockerVehicle();
// The tracked skid-steer robot of the ipd35 suite.
Vehicle TrackedVehicle();

struct ScenarioRun {
  std::string relative_directory;  // "" for a single log, else the log's folder in the suite
  Scenario scenario;
  uint64_t seed;
};

// Throws std::invalid_argument naming the scenario when it is unknown.
std::vector<ScenarioRun> ExpandScenario(const std::string& name, uint64_t seed);

// Names accepted by ExpandScenario, for --help.
std::string ScenarioHelp();

}  // namespace sim
}  // namespace slipgraph
