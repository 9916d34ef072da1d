#include "sim/simulation.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "io/input_error.h"
#include "io/log_writer.h"
#include "sim/diff_drive_sim.h"
#include "sim/rocker_bogie_sim.h"
#include "sim/skid_steer_sim.h"

namespace slipgraph {
namespace sim {

bool EffectSupported(VehicleType type, const std::string& effect) {
  if (type == VehicleType::kDiffDriveCastor) return FindEffect(effect) != nullptr;
  // The kinematic simulators have no force balance: only sensor-side and geometric effects.
  static const char* const kKinematic[] = {"wheel_radius_error", "imu_mounting_pitch",
                                           "clock_offset", "gps_velocity_averaging"};
  for (const char* name : kKinematic) {
    if (effect == name)
      return type == VehicleType::kSkidSteer || effect != "gps_velocity_averaging";
  }
  return false;
}

SimResult Simulate(const Scenario& scenario, uint64_t seed) {
  for (const auto& [effect, value] : scenario.effects) {
    if (!EffectSupported(scenario.vehicle.type, effect)) {
      throw std::invalid_argument("effect '" + effect + "' is not simulated for " +
                                  VehicleTypeName(scenario.vehicle.type) + " vehicles");
    }
  }
  switch (scenario.vehicle.type) {
    case VehicleType::kDiffDriveCastor:
      return SimulateDiffDrive(scenario, seed);
    case VehicleType::kSkidSteer:
      return SimulateSkidSteer(scenario, seed);
    case VehicleType::kRockerBogie6:
      return SimulateRockerBogie(scenario, seed);
  }
  throw std::invalid_argument("unknown vehicle type");
}

namespace {

void EmitTire(YAML::Emitter& e, const TireParams& tire) {
  e << YAML::Flow << YAML::BeginMap << YAML::Key << "C1" << YAML::Value << tire.C1 << YAML::Key
    << "At" << YAML::Value << tire.At << YAML::Key << "C2" << YAML::Value << tire.C2
    << YAML::EndMap;
}

// Keys and values into the map being emitted, in order.
void EmitFields(YAML::Emitter& e, const std::vector<std::pair<const char*, double>>& fields) {
  for (const auto& [key, value] : fields) e << YAML::Key << key << YAML::Value << value;
}

void EmitRolling(YAML::Emitter& e, const RollingParams& rolling) {
  e << YAML::Flow << YAML::BeginMap << YAML::Key << "R1" << YAML::Value << rolling.R1 << YAML::Key
    << "A_roll" << YAML::Value << rolling.A_roll << YAML::Key << "R2" << YAML::Value << rolling.R2
    << YAML::EndMap;
}

}  // namespace

void WriteSimulation(const Scenario& scenario, uint64_t seed, const SimResult& result,
                     const std::string& directory) {
  WriteDriveLog(result.log, directory);
  YAML::Emitter e;
  e << YAML::Comment("Everything that was true in this simulation. Estimators never read it.");
  e << YAML::BeginMap;
  e << YAML::Key << "scenario" << YAML::Value << scenario.name;
  e << YAML::Key << "seed" << YAML::Value << seed;
  e << YAML::Key << "duration_s" << YAML::Value << scenario.duration_s();
  e << YAML::Key << "sim_step_s" << YAML::Value << scenario.sim_step_s;
  e << YAML::Key << "effects" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, value] : scenario.effects) e << YAML::Key << name << YAML::Value << value;
  e << YAML::EndMap;
  e << YAML::Key << "true_wheel_radius_m" << YAML::Value << result.true_wheel_radius_m;
  e << YAML::Key << "imu_accel_offset_mps2" << YAML::Value << YAML::Flow
    << std::vector<double>(result.imu_errors.accel_offset_mps2,
                           result.imu_errors.accel_offset_mps2 + 3);
  e << YAML::Key << "imu_gyro_offset_radps" << YAML::Value << YAML::Flow
    << std::vector<double>(result.imu_errors.gyro_offset_radps,
                           result.imu_errors.gyro_offset_radps + 3);
  e << YAML::Key << "terrain_patches" << YAML::Value << YAML::BeginSeq;
  for (const TerrainPatch& patch : scenario.course.patches) {
    e << YAML::BeginMap << YAML::Key << "s_start_m" << YAML::Value << patch.s_start_m;
    e << YAML::Key << "terrain" << YAML::Value << patch.terrain.name;
    if (patch.terrain.peaked) {
      const PeakedSoil& p = *patch.terrain.peaked;
      e << YAML::Key << "peaked" << YAML::Value << YAML::Flow << YAML::BeginMap;
      EmitFields(e, {{"peak_mu", p.peak_mu},
                     {"stiffness_b", p.stiffness_b},
                     {"shape_c", p.shape_c},
                     {"curvature_e", p.curvature_e},
                     {"roll_c0", p.roll_c0},
                     {"roll_c1_spm", p.roll_c1_spm}});
      e << YAML::EndMap;
    } else if (patch.terrain.track_soil) {
      const TrackSoil& t = *patch.terrain.track_soil;
      e << YAML::Key << "track_soil" << YAML::Value << YAML::Flow << YAML::BeginMap;
      EmitFields(e, {{"cohesion_pa", t.cohesion_pa},
                     {"friction_angle_rad", t.friction_angle_rad},
                     {"shear_modulus_m", t.shear_modulus_m},
                     {"roll_c0", t.roll_c0},
                     {"roll_c1_spm", t.roll_c1_spm}});
      e << YAML::EndMap;
    } else {
      e << YAML::Key << "tire" << YAML::Value;
      EmitTire(e, patch.terrain.tire);
      e << YAML::Key << "rolling" << YAML::Value;
      EmitRolling(e, patch.terrain.rolling);
    }
    e << YAML::Key << "soft" << YAML::Value << patch.terrain.soft << YAML::EndMap;
  }
  e << YAML::EndSeq;
  e << YAML::Key << "hills" << YAML::Value << YAML::BeginSeq;
  for (const Hill& hill : scenario.course.hills) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "s_start_m" << YAML::Value << hill.s_start_m
      << YAML::Key << "length_m" << YAML::Value << hill.length_m << YAML::Key << "peak_grade_rad"
      << YAML::Value << hill.peak_grade_rad << YAML::Key << "peak_cross_slope_rad" << YAML::Value
      << hill.peak_cross_slope_rad << YAML::EndMap;
  }
  e << YAML::EndSeq;
  e << YAML::Key << "holdbacks" << YAML::Value << YAML::BeginSeq;
  for (const HoldBack& hold : scenario.holdbacks) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "t_start_s" << YAML::Value << hold.t_start_s
      << YAML::Key << "t_end_s" << YAML::Value << hold.t_end_s << YAML::EndMap;
  }
  e << YAML::EndSeq;
  if (scenario.vehicle.type == VehicleType::kRockerBogie6) {
    const RockerSpec& r = scenario.rocker;
    e << YAML::Key << "rocker" << YAML::Value << YAML::BeginMap;
    const std::vector<std::pair<const char*, double>> rocker_fields = {
        {"roughness_rms_m", r.roughness_rms_m},
        {"slip_mean", r.slip_mean},
        {"slip_sd", r.slip_sd},
        {"slip_per_slope", r.slip_per_slope},
        {"cycle_rate_hz", r.cycle_rate_hz},
        {"articulation_sd_m", r.articulation_sd_m},
        {"range_sd_m", r.range_sd_m},
        {"range_first_m", r.range_first_m},
        {"range_spacing_m", r.range_spacing_m},
        {"range_points", static_cast<double>(r.range_points)},
        {"base_sinkage_m", r.base_sinkage_m},
        {"soft_sinkage_m", r.soft_sinkage_m},
        {"soft_patch_every_m", r.soft_patch_every_m},
        {"left_extra_sinkage_m", r.left_extra_sinkage_m},
        {"contact_divisor", r.contact_divisor},
        {"slip_correlation_m", r.slip_correlation_m},
        {"soft_extra_slip", r.soft_extra_slip},
        {"middle_extra_sinkage", r.middle_extra_sinkage},
        {"rear_extra_sinkage", r.rear_extra_sinkage},
        {"range_pitch_error_rad", r.range_pitch_error_rad},
    };
    EmitFields(e, rocker_fields);
    const char* const side_names[] = {"left_profile", "right_profile"};
    for (size_t side = 0; side < result.profiles.size() && side < 2; ++side) {
      const TerrainProfile& p = result.profiles[side];
      e << YAML::Key << side_names[side] << YAML::Value << YAML::BeginMap;
      e << YAML::Key << "wavelength_m" << YAML::Value << YAML::Flow << p.wavelength_m;
      e << YAML::Key << "amplitude_m" << YAML::Value << YAML::Flow << p.amplitude_m;
      e << YAML::Key << "phase_rad" << YAML::Value << YAML::Flow << p.phase_rad;
      e << YAML::EndMap;
    }
    e << YAML::EndMap;
  }
  const Actuation& a = scenario.actuation;
  e << YAML::Key << "actuation" << YAML::Value << YAML::Flow << YAML::BeginMap;
  e << YAML::Key << "torque_limit_nm" << YAML::Value << a.torque_limit_nm;
  e << YAML::Key << "wheel_inertia_kgm2" << YAML::Value << a.wheel_inertia_kgm2;
  e << YAML::Key << "kp" << YAML::Value << a.kp_nm_per_radps;
  e << YAML::Key << "ki" << YAML::Value << a.ki_nm_per_rad;
  e << YAML::Key << "tether_stiffness_npm" << YAML::Value << a.tether_stiffness_npm;
  e << YAML::Key << "tether_damping_nspm" << YAML::Value << a.tether_damping_nspm;
  e << YAML::EndMap;
  const SensorSpec& s = scenario.sensors;
  const SensorMismatch& sm = s.mismatch;
  // The mismatch suites' truth, for the soils their patches carry.
  const auto any_patch = [&](bool (*has)(const TerrainType&)) {
    return std::any_of(scenario.course.patches.begin(), scenario.course.patches.end(),
                       [has](const TerrainPatch& p) { return has(p.terrain); });
  };
  std::vector<std::pair<const char*, double>> mismatch_fields;
  if (any_patch([](const TerrainType& t) { return t.peaked.has_value(); })) {
    mismatch_fields.insert(
        mismatch_fields.end(),
        {{"relaxation_length_m", scenario.mismatch.relaxation_length_m},
         {"radius_load_sensitivity", scenario.mismatch.radius_load_sensitivity},
         {"attitude_error_sd_rad", sm.attitude_error_sd_rad},
         {"attitude_error_tau_s", sm.attitude_error_tau_s},
         {"vibration_sd_mps2_per_mps", sm.vibration_sd_mps2_per_mps},
         {"vibration_hz", sm.vibration_hz},
         {"vibration_damping", sm.vibration_damping},
         {"gps_velocity_interval_mean", sm.gps_velocity_interval_mean ? 1.0 : 0.0}});
  }
  if (any_patch([](const TerrainType& t) { return t.track_soil.has_value(); })) {
    const VehicleMismatch& m = scenario.mismatch;
    mismatch_fields.insert(mismatch_fields.end(),
                           {{"track_contact_length_m", m.tracks.contact_length_m},
                            {"track_belt_width_m", m.tracks.belt_width_m},
                            {"track_soil_variation_sd", m.track_soil_variation_sd},
                            {"track_soil_correlation_m", m.track_soil_correlation_m}});
  }
  if (!mismatch_fields.empty()) {
    e << YAML::Key << "mismatch" << YAML::Value << YAML::BeginMap;
    EmitFields(e, mismatch_fields);
    e << YAML::EndMap;
  }
  e << YAML::Key << "sensors" << YAML::Value << YAML::BeginMap;
  const std::vector<std::pair<const char*, double>> sensor_fields = {
      {"imu_rate_hz", s.imu_rate_hz},
      {"wheel_rate_hz", s.wheel_rate_hz},
      {"gps_rate_hz", s.gps_rate_hz},
      {"attitude_rate_hz", s.attitude_rate_hz},
      {"pose_rate_hz", s.pose_rate_hz},
      {"encoder_counts_per_rev", static_cast<double>(s.encoder_counts_per_rev)},
      {"sd_accel_mps2", s.sd_accel_mps2},
      {"sd_gyro_radps", s.sd_gyro_radps},
      {"accel_bias_sd_mps2", s.accel_bias_sd_mps2},
      {"accel_bias_tau_s", s.accel_bias_tau_s},
      {"gyro_bias_sd_radps", s.gyro_bias_sd_radps},
      {"gyro_bias_tau_s", s.gyro_bias_tau_s},
      {"sd_omega_radps", s.sd_omega_radps},
      {"gps_sd_xy_m", s.gps_sd_xy_m},
      {"gps_sd_v_mps", s.gps_sd_v_mps},
      {"attitude_sd_rad", s.attitude_sd_rad},
      {"pose_sd_xy_m", s.pose_sd_xy_m},
      {"pose_sd_yaw_rad", s.pose_sd_yaw_rad},
  };
  EmitFields(e, sensor_fields);
  e << YAML::EndMap;
  e << YAML::EndMap;
  const std::string path = (std::filesystem::path(directory) / "sim.yaml").string();
  std::ofstream out(path);
  if (!out) throw InputError(path, 0, "", "", "cannot open file for writing");
  out << e.c_str() << "\n";
}

}  // namespace sim
}  // namespace slipgraph
