#include "io/yaml_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "factors/catalogue_terms.h"
#include "io/input_error.h"
#include "io/text_file.h"
#include "io/yaml_errors.h"
#include "model/effect_catalogue.h"

namespace slipgraph {
namespace {

// A numeric key and where it goes: a real number, or a whole one (a count).
struct NumberField {
  NumberField(const char* key, double* target, bool needed)
      : key(key), target(target), needed(needed) {}
  NumberField(const char* key, int* whole, bool needed) : key(key), whole(whole), needed(needed) {}
  const char* key;
  double* target = nullptr;
  int* whole = nullptr;
  bool needed;
};

// The tire and rolling laws' keys, onto `tire` and `rolling` (vehicle.yaml, the model file, the
// law's sd and soils).
std::vector<NumberField> TireFields(TireParams* tire, bool needed) {
  return {{"C1", &tire->C1, needed}, {"At", &tire->At, needed}, {"C2", &tire->C2, needed}};
}
// The model file's tire_sd: the coefficients' sd and the sd of the log of the slope.
std::vector<NumberField> TireSdFields(ModelConfig* m) {
  std::vector<NumberField> fields = TireFields(&m->tire_sd, false);
  fields.push_back({"slip_stiffness", &m->tire_slip_stiffness_relative_sd, false});
  return fields;
}
std::vector<NumberField> RollingFields(RollingParams* rolling, bool needed) {
  return {{"R1", &rolling->R1, needed},
          {"A_roll", &rolling->A_roll, needed},
          {"R2", &rolling->R2, needed}};
}

[[noreturn]] void Fail(const std::string& path, const YAML::Node& node, const std::string& key,
                       const std::string& value, const std::string& what) {
  const YAML::Mark mark = node.Mark();
  const int line = mark.is_null() ? 0 : mark.line + 1;
  throw InputError(path, line, key, value, what);
}

double ReadNumber(const std::string& path, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) Fail(path, node, key, "", "expected a number");
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    Fail(path, node, key, node.Scalar(), "not a number");
  }
  if (!std::isfinite(value)) Fail(path, node, key, node.Scalar(), "not a finite number");
  return value;
}

bool ReadBool(const std::string& path, const YAML::Node& node, const std::string& key) {
  bool value = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
    Fail(path, node, key, node.IsScalar() ? node.Scalar() : "", "expected true or false");
  }
  return value;
}

// Reads the listed numeric keys of `map`. A missing needed key is an error. Keys not listed are
// errors when `strict`, warnings otherwise.
void ReadNumbers(const std::string& path, const YAML::Node& map, const std::string& prefix,
                 const std::vector<NumberField>& fields, bool strict,
                 std::vector<std::string>* warnings, const std::set<std::string>& sections = {}) {
  if (!map.IsMap()) Fail(path, map, prefix, "", "expected a mapping");
  for (const NumberField& field : fields) {
    const YAML::Node value = map[field.key];
    if (!value) {
      if (field.needed) Fail(path, map, prefix + field.key, "", "missing key");
      continue;
    }
    const double number = ReadNumber(path, value, prefix + field.key);
    if (field.whole == nullptr) {
      *field.target = number;
      continue;
    }
    if (number != std::floor(number)) {
      Fail(path, value, prefix + field.key, value.Scalar(), "expected a whole number");
    }
    if (std::fabs(number) > std::numeric_limits<int>::max()) {
      Fail(path, value, prefix + field.key, value.Scalar(), "out of range for a count");
    }
    *field.whole = static_cast<int>(number);
  }
  for (const auto& entry : map) {
    const std::string key = entry.first.as<std::string>();
    bool known = sections.count(key) > 0;
    for (const NumberField& field : fields) known = known || key == field.key;
    if (known) continue;
    if (strict) Fail(path, entry.first, prefix + key, "", "unknown key");
    if (warnings) warnings->push_back(path + ": unknown key '" + prefix + key + "' ignored");
  }
}

}  // namespace

namespace {

Vehicle ReadVehicle(const std::string& path, const std::string& text,
                    std::vector<std::string>* warnings) {
  const YAML::Node root = LoadYaml(path, text);
  if (!root.IsMap()) throw InputError(path, 1, "", "", "expected a mapping at the top level");
  Vehicle v;
  const YAML::Node type = root["type"];
  if (!type) Fail(path, root, "type", "", "missing key");
  if (!ParseVehicleType(type.as<std::string>(""), &v.type)) {
    Fail(path, type, "type", type.as<std::string>(""),
         "unknown vehicle type (expected diff_drive_castor, skid_steer or rocker_bogie6)");
  }
  v.name = root["name"] ? root["name"].as<std::string>("") : std::string();

  const bool castor = v.type == VehicleType::kDiffDriveCastor;
  const bool rocker = v.type == VehicleType::kRockerBogie6;
  std::vector<NumberField> top = {
      {"mass", &v.mass_kg, true},
      {"yaw_inertia", &v.yaw_inertia_kgm2, true},
      {"wheel_radius", &v.wheel_radius_m, true},
      {"track_width", &v.track_width_m, true},
      {"cg_to_front", &v.cg_to_front_m, castor},
      {"cg_to_rear", &v.cg_to_rear_m, castor},
      {"cg_height", &v.cg_height_m, true},
      {"axle_spacing", &v.axle_spacing_m, rocker},
  };
  ReadNumbers(
      path, root, "", top, false, warnings,
      {"name", "type", "tire", "rolling", "tire_sd", "rolling_sd", "law_samples", "sensors"});
  for (const NumberField& field : top) {
    if (root[field.key] && *field.target <= 0.0) {
      Fail(path, root[field.key], field.key, root[field.key].Scalar(), "must be positive");
    }
  }

  const YAML::Node tire = root["tire"];
  if (!tire) Fail(path, root, "tire", "", "missing key");
  ReadNumbers(path, tire, "tire.", TireFields(&v.tire, true), false, warnings);
  const YAML::Node rolling = root["rolling"];
  if (!rolling) Fail(path, root, "rolling", "", "missing key");
  ReadNumbers(path, rolling, "rolling.", RollingFields(&v.rolling, true), false, warnings);
  // Optional (an extension): the coefficients' sd when the law is a fit the terrain may not
  // follow.
  const struct {
    const char* key;
    std::vector<NumberField> fields;
  } law_sd[] = {{"tire_sd", TireFields(&v.tire_sd, false)},
                {"rolling_sd", RollingFields(&v.rolling_sd, false)}};
  for (const auto& section : law_sd) {
    const YAML::Node node = root[section.key];
    if (!node) continue;
    const std::string prefix = std::string(section.key) + ".";
    ReadNumbers(path, node, prefix, section.fields, false, warnings);
    for (const NumberField& field : section.fields) {
      if (node[field.key] && *field.target < 0.0) {
        Fail(path, node[field.key], prefix + field.key, node[field.key].Scalar(),
             "must be non-negative");
      }
    }
  }
  // Optional: the laws of the soils the law was fitted over, every coefficient of each.
  if (const YAML::Node samples = root["law_samples"]) {
    if (!samples.IsSequence()) Fail(path, samples, "law_samples", "", "expected a sequence");
    for (size_t i = 0; i < samples.size(); ++i) {
      LawSample soil;
      const std::string prefix = "law_samples[" + std::to_string(i) + "].";
      std::vector<NumberField> fields = TireFields(&soil.tire, true);
      for (const NumberField& field : RollingFields(&soil.rolling, true)) fields.push_back(field);
      ReadNumbers(path, samples[i], prefix, fields, false, warnings);
      const struct {
        const char* key;
        double value;
        bool zero_allowed;
      } checks[] = {{"C1", soil.tire.C1, false},
                    {"At", soil.tire.At, false},
                    {"A_roll", soil.rolling.A_roll, false},
                    {"R1", soil.rolling.R1, true},
                    {"R2", soil.rolling.R2, true}};
      for (const auto& check : checks) {
        if (check.value < 0.0 || (!check.zero_allowed && check.value == 0.0)) {
          Fail(path, samples[i][check.key], prefix + check.key, samples[i][check.key].Scalar(),
               check.zero_allowed ? "must be non-negative" : "must be positive");
        }
      }
      v.law_samples.push_back(soil);
    }
  }

  const YAML::Node sensors = root["sensors"];
  const struct {
    const char* section;
    std::vector<NumberField> fields;
  } sensor_sections[] = {
      {"imu",
       {{"sd_accel", &v.sensors.imu_sd_accel_mps2, true},
        {"sd_gyro", &v.sensors.imu_sd_gyro_radps, true}}},
      {"wheels", {{"sd_omega", &v.sensors.wheels_sd_omega_radps, true}}},
      {"gps", {{"sd_xy", &v.sensors.gps_sd_xy_m, true}, {"sd_v", &v.sensors.gps_sd_v_mps, true}}},
  };
  for (const auto& section : sensor_sections) {
    const YAML::Node node = sensors ? sensors[section.section] : YAML::Node();
    const std::string name = std::string("sensors.") + section.section;
    if (!node || node.IsNull()) {
      v.defaulted_keys.push_back(name);
      continue;
    }
    ReadNumbers(path, node, name + ".", section.fields, false, warnings);
    // A standard deviation of zero weighs a sensor as exact: the filter's covariance collapses.
    for (const NumberField& field : section.fields) {
      if (node[field.key] && !(*field.target > 0.0)) {
        Fail(path, node[field.key], name + "." + field.key, node[field.key].Scalar(),
             "must be positive (a standard deviation)");
      }
    }
  }
  return v;
}

}  // namespace

Vehicle ReadVehicleYaml(const std::string& path, std::vector<std::string>* warnings) {
  return ParseVehicleYaml(path, ReadTextFile(path), warnings);
}

Vehicle ParseVehicleYaml(const std::string& name, const std::string& text,
                         std::vector<std::string>* warnings) {
  return NamingYamlErrors(name, [&] { return ReadVehicle(name, text, warnings); });
}

namespace {

ModelConfig ReadModel(const std::string& path, const std::string& text, const Vehicle& vehicle) {
  ModelConfig m = DefaultModelConfig(vehicle);
  const YAML::Node root = LoadYaml(path, text);
  if (root.IsNull()) return m;  // an empty file changes nothing
  if (!root.IsMap()) throw InputError(path, 1, "", "", "expected a mapping at the top level");

  ProcessNoiseConfig& q = m.process;
  WeakConstraintConfig& wc = m.weak_constraints;
  ImmobilizationConfig& im = m.immobilization;
  const std::vector<std::pair<std::string, std::vector<NumberField>>> sections = {
      {"tire", TireFields(&m.tire, false)},
      {"rolling", RollingFields(&m.rolling, false)},
      {"tire_sd", TireSdFields(&m)},
      {"rolling_sd", RollingFields(&m.rolling_sd, false)},
      {"process_noise",
       {{"v_bx", &q.v_bx_mps2_per_sqrt_hz, false},
        {"a_dist", &q.a_dist_mps3_per_sqrt_hz, false},
        {"a_dist_max", &q.a_dist_max_mps3_per_sqrt_hz, false},
        {"a_dist_adapt_samples", &q.a_dist_adapt_samples, false},
        {"a_dist_decay_tau", &q.a_dist_decay_tau_s, false},
        {"omega", &q.omega_radps2_per_sqrt_hz, false},
        {"yaw_rate", &q.yaw_rate_radps2_per_sqrt_hz, false},
        {"accel_bias_sd", &q.accel_bias_sd_mps2, false},
        {"accel_bias_tau", &q.accel_bias_tau_s, false},
        {"gyro_bias_sd", &q.gyro_bias_sd_radps, false},
        {"gyro_bias_tau", &q.gyro_bias_tau_s, false},
        {"attitude_error_walk", &q.attitude_error_walk_s, false}}},
      {"measurement_noise",
       {{"imu_sd_accel", &m.measurement.imu_sd_accel_mps2, false},
        {"imu_sd_gyro", &m.measurement.imu_sd_gyro_radps, false},
        {"wheels_sd_omega", &m.measurement.wheels_sd_omega_radps, false},
        {"gps_sd_xy", &m.measurement.gps_sd_xy_m, false},
        {"gps_sd_v", &m.measurement.gps_sd_v_mps, false}}},
      {"weak_constraints",
       {{"sd_oppose_motion", &wc.sd_oppose_motion, false},
        {"oppose_motion_cauchy_scale", &wc.oppose_motion_cauchy_scale_mps2, false},
        {"sd_act_quickly", &wc.sd_act_quickly, false},
        {"sd_no_pull_back", &wc.sd_no_pull_back, false},
        {"sd_at_rest", &wc.sd_at_rest, false},
        {"sd_bound", &wc.sd_bound, false},
        {"min_slip_rate", &wc.min_slip_rate_per_s, false},
        {"slip_threshold", &wc.slip_threshold, false},
        {"decay_alpha", &wc.decay_alpha, false},
        {"stop_time", &wc.stop_time_s, false},
        {"still_smoothing", &wc.still_smoothing_s, false},
        {"max_v_bx", &wc.max_v_bx_mps, false},
        {"max_accel_bias", &wc.max_accel_bias_mps2, false},
        {"max_a_dist", &wc.max_a_dist_mps2, false},
        {"max_gyro_bias", &wc.max_gyro_bias_radps, false},
        {"max_v_bx_rate", &wc.max_v_bx_rate_mps2, false},
        {"max_accel_bias_rate", &wc.max_accel_bias_rate_mps3, false}}},
      {"immobilization",
       {{"ema_samples", &im.ema_samples, false},
        {"slip_threshold", &im.slip_threshold, false},
        {"low_speed_threshold_add", &im.low_speed_threshold_add, false},
        {"low_speed", &im.low_speed_mps, false},
        {"min_wheel_speed", &im.min_wheel_speed_mps, false},
        {"velocity_sd_margin", &im.velocity_sd_margin, false}}},
      {"slip_persistence",
       {{"interval", &m.slip_persistence.interval_s, false},
        {"sd", &m.slip_persistence.sd_mps, false},
        {"gate", &m.slip_persistence.gate_sd, false},
        {"smoothing", &m.slip_persistence.smoothing_s, false},
        {"min_rim_speed", &m.slip_persistence.min_rim_speed_mps, false},
        {"max_rim_acceleration", &m.slip_persistence.max_rim_acceleration_mps2, false},
        {"lasting_intervals", &m.slip_persistence.lasting_intervals, false},
        {"max_lasting_error", &m.slip_persistence.max_lasting_error_mps2, false}}},
      {"offsets",
       {{"init_samples", &m.offset_init_samples, false},
        {"ema_samples", &m.offset_ema_samples, false},
        {"rest_guard", &m.offset_rest_guard_s, false}}},
      {"calibration",
       {{"wheel_radius_scale_left", &m.calibration.wheel_radius_scale_left, false},
        {"wheel_radius_scale_right", &m.calibration.wheel_radius_scale_right, false},
        {"track_width", &m.calibration.track_width_m, false},
        {"imu_time_offset", &m.calibration.imu_time_offset_s, false},
        {"wheels_time_offset", &m.calibration.wheels_time_offset_s, false},
        {"imu_mounting_pitch", &m.calibration.imu_mounting_pitch_rad, false}}},
      {"tire_uncertainty",
       {{"relative_sd", &m.tire_uncertainty.relative_sd, false},
        {"slip_relative_sd", &m.tire_uncertainty.slip_relative_sd, false},
        {"slip_floor", &m.tire_uncertainty.slip_floor_mps, false},
        {"floor", &m.tire_uncertainty.floor_mps2, false},
        {"correlation_time", &m.tire_uncertainty.correlation_time_s, false}}},
  };
  for (const auto& entry : root) {
    const std::string key = entry.first.as<std::string>();
    if (key == "gravity") {
      m.gravity_mps2 = ReadNumber(path, entry.second, key);
      continue;
    }
    if (key == "gnss_heading_from_course") {
      m.gnss_heading_from_course = ReadBool(path, entry.second, key);
      continue;
    }
    if (key == "effect_windows") {
      if (!entry.second.IsSequence()) {
        Fail(path, entry.second, key, "", "expected a list of {effect, from, to}");
      }
      m.effect_windows.clear();
      for (const auto& window : entry.second) {
        if (!window.IsMap()) Fail(path, window, key, "", "expected {effect, from, to}");
        ModelConfig::EffectWindow w;
        bool have_effect = false, have_from = false, have_to = false;
        for (const auto& field : window) {
          const std::string name = field.first.as<std::string>();
          if (name == "effect") {
            w.effect = field.second.as<std::string>(), have_effect = true;
          } else if (name == "from") {
            w.t_start_s = ReadNumber(path, field.second, key + ".from"), have_from = true;
          } else if (name == "to") {
            w.t_end_s = ReadNumber(path, field.second, key + ".to"), have_to = true;
          } else {
            Fail(path, field.first, key + "." + name, "", "unknown key");
          }
        }
        if (!have_effect || !have_from || !have_to) {
          Fail(path, window, key, "", "each window needs effect, from and to");
        }
        m.effect_windows.push_back(w);
      }
      continue;
    }
    if (key == "effects") {
      if (!entry.second.IsSequence()) Fail(path, entry.second, key, "", "expected a list of names");
      m.effects.clear();
      for (const auto& effect : entry.second) {
        const std::string name = effect.as<std::string>();
        const EffectInfo* info = FindEffect(name);
        if (CatalogueTerms().Find(name) == nullptr &&
            (info == nullptr || !info->in_model_catalogue)) {
          Fail(path, effect, key, name, "unknown effect (not in the model's effect catalogue)");
        }
        m.effects.push_back(name);
      }
      continue;
    }
    bool known = false;
    for (const auto& section : sections) {
      if (section.first != key) continue;
      ReadNumbers(path, entry.second, key + ".", section.second, true, nullptr);
      known = true;
    }
    if (!known) Fail(path, entry.first, key, "", "unknown key");
  }
  std::string error;
  if (!m.IsValid(&error)) throw InputError(path, 0, "", "", "invalid model: " + error);
  // The effects that act on windows of the drive need them, and only they take them.
  std::string windowed;
  for (const EffectTerm& term : CatalogueTerms().all()) {
    if (term.acts_on_windows) windowed += (windowed.empty() ? "" : ", ") + term.name;
  }
  for (const ModelConfig::EffectWindow& w : m.effect_windows) {
    const EffectTerm* term = CatalogueTerms().Find(w.effect);
    if (term == nullptr || !term->acts_on_windows) {
      throw InputError(path, 0, "effect_windows", w.effect,
                       "invalid model: effect_windows: '" + w.effect +
                           "' does not act on windows (only " + windowed + ")");
    }
  }
  for (const std::string& name : m.effects) {
    const EffectTerm* term = CatalogueTerms().Find(name);
    if (term == nullptr || !term->acts_on_windows) continue;
    if (std::none_of(m.effect_windows.begin(), m.effect_windows.end(),
                     [&](const ModelConfig::EffectWindow& w) { return w.effect == name; })) {
      throw InputError(path, 0, "effects", name,
                       "invalid model: effects: " + name +
                           " needs effect_windows (the times it acts; `slipgraph diagnose --with " +
                           name + "` takes them from what it finds)");
    }
  }
  return m;
}

}  // namespace

ModelConfig ReadModelYaml(const std::string& path, const Vehicle& vehicle) {
  return ParseModelYaml(path, ReadTextFile(path), vehicle);
}

ModelConfig ReadModelOrNominal(const std::string& model_path, const Vehicle& vehicle) {
  return model_path.empty() ? DefaultModelConfig(vehicle) : ReadModelYaml(model_path, vehicle);
}

ModelConfig ModelForLog(DriveLog* log, const std::string& model_path) {
  const ModelConfig model = ReadModelOrNominal(model_path, log->vehicle);
  ApplyCalibration(model, log);
  return model;
}

ModelConfig ParseModelYaml(const std::string& name, const std::string& text,
                           const Vehicle& vehicle) {
  return NamingYamlErrors(name, [&] { return ReadModel(name, text, vehicle); });
}

void WriteVehicleYaml(const Vehicle& v, std::ostream& out) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  e << YAML::Key << "name" << YAML::Value << v.name;
  e << YAML::Key << "type" << YAML::Value << VehicleTypeName(v.type);
  e << YAML::Key << "mass" << YAML::Value << v.mass_kg;
  e << YAML::Key << "yaw_inertia" << YAML::Value << v.yaw_inertia_kgm2;
  e << YAML::Key << "wheel_radius" << YAML::Value << v.wheel_radius_m;
  e << YAML::Key << "track_width" << YAML::Value << v.track_width_m;
  if (v.type == VehicleType::kDiffDriveCastor) {
    e << YAML::Key << "cg_to_front" << YAML::Value << v.cg_to_front_m;
    e << YAML::Key << "cg_to_rear" << YAML::Value << v.cg_to_rear_m;
  }
  e << YAML::Key << "cg_height" << YAML::Value << v.cg_height_m;
  if (v.type == VehicleType::kRockerBogie6) {
    e << YAML::Key << "axle_spacing" << YAML::Value << v.axle_spacing_m;
  }
  e << YAML::Key << "tire" << YAML::Value << YAML::Flow << YAML::BeginMap;
  e << YAML::Key << "C1" << YAML::Value << v.tire.C1 << YAML::Key << "At" << YAML::Value
    << v.tire.At << YAML::Key << "C2" << YAML::Value << v.tire.C2 << YAML::EndMap;
  e << YAML::Key << "rolling" << YAML::Value << YAML::Flow << YAML::BeginMap;
  e << YAML::Key << "R1" << YAML::Value << v.rolling.R1 << YAML::Key << "A_roll" << YAML::Value
    << v.rolling.A_roll << YAML::Key << "R2" << YAML::Value << v.rolling.R2 << YAML::EndMap;
  if (v.tire_sd.C1 > 0.0 || v.tire_sd.At > 0.0 || v.tire_sd.C2 > 0.0) {
    e << YAML::Key << "tire_sd" << YAML::Value << YAML::Flow << YAML::BeginMap;
    e << YAML::Key << "C1" << YAML::Value << v.tire_sd.C1 << YAML::Key << "At" << YAML::Value
      << v.tire_sd.At << YAML::Key << "C2" << YAML::Value << v.tire_sd.C2 << YAML::EndMap;
  }
  if (v.rolling_sd.R1 > 0.0 || v.rolling_sd.A_roll > 0.0 || v.rolling_sd.R2 > 0.0) {
    e << YAML::Key << "rolling_sd" << YAML::Value << YAML::Flow << YAML::BeginMap;
    e << YAML::Key << "R1" << YAML::Value << v.rolling_sd.R1 << YAML::Key << "A_roll" << YAML::Value
      << v.rolling_sd.A_roll << YAML::Key << "R2" << YAML::Value << v.rolling_sd.R2 << YAML::EndMap;
  }
  if (!v.law_samples.empty()) {
    e << YAML::Key << "law_samples" << YAML::Value << YAML::BeginSeq;
    for (const LawSample& soil : v.law_samples) {
      e << YAML::Flow << YAML::BeginMap << YAML::Key << "C1" << YAML::Value << soil.tire.C1
        << YAML::Key << "At" << YAML::Value << soil.tire.At << YAML::Key << "C2" << YAML::Value
        << soil.tire.C2 << YAML::Key << "R1" << YAML::Value << soil.rolling.R1 << YAML::Key
        << "A_roll" << YAML::Value << soil.rolling.A_roll << YAML::Key << "R2" << YAML::Value
        << soil.rolling.R2 << YAML::EndMap;
    }
    e << YAML::EndSeq;
  }
  e << YAML::Key << "sensors" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "imu" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "sd_accel"
    << YAML::Value << v.sensors.imu_sd_accel_mps2 << YAML::Key << "sd_gyro" << YAML::Value
    << v.sensors.imu_sd_gyro_radps << YAML::EndMap;
  e << YAML::Key << "wheels" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key
    << "sd_omega" << YAML::Value << v.sensors.wheels_sd_omega_radps << YAML::EndMap;
  e << YAML::Key << "gps" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "sd_xy"
    << YAML::Value << v.sensors.gps_sd_xy_m << YAML::Key << "sd_v" << YAML::Value
    << v.sensors.gps_sd_v_mps << YAML::EndMap;
  e << YAML::EndMap << YAML::EndMap;
  out << e.c_str() << "\n";
}

void WriteModelYaml(const ModelConfig& m, std::ostream& out) {
  const ProcessNoiseConfig& q = m.process;
  const WeakConstraintConfig& wc = m.weak_constraints;
  const ImmobilizationConfig& im = m.immobilization;
  YAML::Emitter e;
  e << YAML::BeginMap;
  e << YAML::Key << "gravity" << YAML::Value << m.gravity_mps2;
  e << YAML::Key << "gnss_heading_from_course" << YAML::Value << m.gnss_heading_from_course;
  auto section = [&e](const char* name, const std::vector<std::pair<const char*, double>>& fields) {
    e << YAML::Key << name << YAML::Value << YAML::BeginMap;
    for (const auto& field : fields) e << YAML::Key << field.first << YAML::Value << field.second;
    e << YAML::EndMap;
  };
  section("tire", {{"C1", m.tire.C1}, {"At", m.tire.At}, {"C2", m.tire.C2}});
  section("rolling", {{"R1", m.rolling.R1}, {"A_roll", m.rolling.A_roll}, {"R2", m.rolling.R2}});
  section("tire_sd", {{"C1", m.tire_sd.C1},
                      {"At", m.tire_sd.At},
                      {"C2", m.tire_sd.C2},
                      {"slip_stiffness", m.tire_slip_stiffness_relative_sd}});
  section("rolling_sd",
          {{"R1", m.rolling_sd.R1}, {"A_roll", m.rolling_sd.A_roll}, {"R2", m.rolling_sd.R2}});
  section("process_noise", {{"v_bx", q.v_bx_mps2_per_sqrt_hz},
                            {"a_dist", q.a_dist_mps3_per_sqrt_hz},
                            {"a_dist_max", q.a_dist_max_mps3_per_sqrt_hz},
                            {"a_dist_adapt_samples", q.a_dist_adapt_samples},
                            {"a_dist_decay_tau", q.a_dist_decay_tau_s},
                            {"omega", q.omega_radps2_per_sqrt_hz},
                            {"yaw_rate", q.yaw_rate_radps2_per_sqrt_hz},
                            {"accel_bias_sd", q.accel_bias_sd_mps2},
                            {"accel_bias_tau", q.accel_bias_tau_s},
                            {"gyro_bias_sd", q.gyro_bias_sd_radps},
                            {"gyro_bias_tau", q.gyro_bias_tau_s},
                            {"attitude_error_walk", q.attitude_error_walk_s}});
  section("measurement_noise", {{"imu_sd_accel", m.measurement.imu_sd_accel_mps2},
                                {"imu_sd_gyro", m.measurement.imu_sd_gyro_radps},
                                {"wheels_sd_omega", m.measurement.wheels_sd_omega_radps},
                                {"gps_sd_xy", m.measurement.gps_sd_xy_m},
                                {"gps_sd_v", m.measurement.gps_sd_v_mps}});
  section("weak_constraints", {{"sd_oppose_motion", wc.sd_oppose_motion},
                               {"oppose_motion_cauchy_scale", wc.oppose_motion_cauchy_scale_mps2},
                               {"sd_act_quickly", wc.sd_act_quickly},
                               {"sd_no_pull_back", wc.sd_no_pull_back},
                               {"sd_at_rest", wc.sd_at_rest},
                               {"sd_bound", wc.sd_bound},
                               {"min_slip_rate", wc.min_slip_rate_per_s},
                               {"slip_threshold", wc.slip_threshold},
                               {"decay_alpha", wc.decay_alpha},
                               {"stop_time", wc.stop_time_s},
                               {"still_smoothing", wc.still_smoothing_s},
                               {"max_v_bx", wc.max_v_bx_mps},
                               {"max_accel_bias", wc.max_accel_bias_mps2},
                               {"max_a_dist", wc.max_a_dist_mps2},
                               {"max_gyro_bias", wc.max_gyro_bias_radps},
                               {"max_v_bx_rate", wc.max_v_bx_rate_mps2},
                               {"max_accel_bias_rate", wc.max_accel_bias_rate_mps3}});
  section("immobilization", {{"ema_samples", im.ema_samples},
                             {"slip_threshold", im.slip_threshold},
                             {"low_speed_threshold_add", im.low_speed_threshold_add},
                             {"low_speed", im.low_speed_mps},
                             {"min_wheel_speed", im.min_wheel_speed_mps},
                             {"velocity_sd_margin", im.velocity_sd_margin}});
  const SlipPersistenceConfig& sp = m.slip_persistence;
  section("slip_persistence", {{"interval", sp.interval_s},
                               {"sd", sp.sd_mps},
                               {"gate", sp.gate_sd},
                               {"smoothing", sp.smoothing_s},
                               {"min_rim_speed", sp.min_rim_speed_mps},
                               {"max_rim_acceleration", sp.max_rim_acceleration_mps2},
                               {"lasting_intervals", static_cast<double>(sp.lasting_intervals)},
                               {"max_lasting_error", sp.max_lasting_error_mps2}});
  section("offsets", {{"init_samples", static_cast<double>(m.offset_init_samples)},
                      {"ema_samples", m.offset_ema_samples},
                      {"rest_guard", m.offset_rest_guard_s}});
  section("calibration", {{"wheel_radius_scale_left", m.calibration.wheel_radius_scale_left},
                          {"wheel_radius_scale_right", m.calibration.wheel_radius_scale_right},
                          {"track_width", m.calibration.track_width_m},
                          {"imu_time_offset", m.calibration.imu_time_offset_s},
                          {"wheels_time_offset", m.calibration.wheels_time_offset_s},
                          {"imu_mounting_pitch", m.calibration.imu_mounting_pitch_rad}});
  section("tire_uncertainty", {{"relative_sd", m.tire_uncertainty.relative_sd},
                               {"slip_relative_sd", m.tire_uncertainty.slip_relative_sd},
                               {"slip_floor", m.tire_uncertainty.slip_floor_mps},
                               {"floor", m.tire_uncertainty.floor_mps2},
                               {"correlation_time", m.tire_uncertainty.correlation_time_s}});
  e << YAML::Key << "effects" << YAML::Value << YAML::Flow << m.effects;
  if (!m.effect_windows.empty()) {
    e << YAML::Key << "effect_windows" << YAML::Value << YAML::BeginSeq;
    for (const ModelConfig::EffectWindow& w : m.effect_windows) {
      e << YAML::Flow << YAML::BeginMap << YAML::Key << "effect" << YAML::Value << w.effect
        << YAML::Key << "from" << YAML::Value << w.t_start_s << YAML::Key << "to" << YAML::Value
        << w.t_end_s << YAML::EndMap;
    }
    e << YAML::EndSeq;
  }
  e << YAML::EndMap;
  out << e.c_str() << "\n";
}

}  // namespace slipgraph
