// Running a scenario: the simulated drive log (with truth and events) and everything a reader
// of sim.yaml needs to know about what was true.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "sim/scenario.h"
#include "sim/sensor_models.h"

namespace slipgraph {
namespace sim {

struct SimResult {
  DriveLog log;  // vehicle.yaml (nominal), sensor files, truth.csv, events.csv
  ImuErrors imu_errors;
  double true_wheel_radius_m = 0.0;
  std::vector<TerrainProfile> profiles;  // rocker_bogie6: left and right terrain profiles
};

// Whether the simulator of a vehicle type applies `effect` (the kinematic skid-steer and rocker
// simulators apply only the sensor-side and geometric effects).
bool EffectSupported(VehicleType type, const std::string& effect);

// Deterministic: the same scenario and seed give the same log, bit for bit. Throws
// std::invalid_argument for an effect the vehicle's simulator does not apply.
SimResult Simulate(const Scenario& scenario, uint64_t seed);

// Writes the log and sim.yaml (every true parameter and effect; no estimator reads it) to
// `directory`.
void WriteSimulation(const Scenario& scenario, uint64_t seed, const SimResult& result,
                     const std::string& directory);

}  // namespace sim
}  // namespace slipgraph
