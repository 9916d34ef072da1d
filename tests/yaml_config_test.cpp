#include "io/yaml_config.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "io/input_error.h"
#include "tests/test_log_files.h"

namespace slipgraph {
namespace {

Vehicle LagrVehicle() {
  const std::string dir = testing::FreshDirectory("vehicle");
  testing::WriteText(dir, "vehicle.yaml", testing::kLagrVehicleYaml);
  std::vector<std::string> warnings;
  return ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
}

std::string WriteModel(const std::string& text) {
  const std::string dir = testing::FreshDirectory("model");
  testing::WriteText(dir, "model.yaml", text);
  return dir + "/model.yaml";
}

TEST(YamlConfig, ModelFileOverridesVehicleAndDefaults) {
  const Vehicle vehicle = LagrVehicle();
  const ModelConfig m = ReadModelYaml(
      WriteModel("tire: {C1: 0.64}\nprocess_noise:\n  a_dist: 3.0\neffects: [quadratic_drag]\n"),
      vehicle);
  EXPECT_DOUBLE_EQ(m.tire.C1, 0.64);  // overridden
  EXPECT_DOUBLE_EQ(m.tire.At, 20.0);  // from vehicle.yaml
  EXPECT_DOUBLE_EQ(m.process.a_dist_mps3_per_sqrt_hz, 3.0);
  EXPECT_DOUBLE_EQ(m.process.accel_bias_tau_s, ProcessNoiseConfig().accel_bias_tau_s);
  EXPECT_DOUBLE_EQ(m.measurement.gps_sd_v_mps, 0.1);  // from vehicle.yaml sensors
  EXPECT_EQ(m.effects, std::vector<std::string>{"quadratic_drag"});
}

TEST(YamlConfig, UnknownModelKeyIsAnErrorNamingIt) {
  try {
    ReadModelYaml(WriteModel("tire: {C1: 0.6}\nprocess_noise:\n  a_distt: 3.0\n"), LagrVehicle());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.column(), "process_noise.a_distt");
    EXPECT_EQ(e.line(), 3);
  }
  EXPECT_THROW(ReadModelYaml(WriteModel("tyre: {C1: 0.6}\n"), LagrVehicle()), InputError);
}

// yaml-cpp keeps both entries of a repeated key and a lookup takes the first: an error instead.
TEST(YamlConfig, ADuplicateKeyIsAnErrorNamingIt) {
  try {
    ReadModelYaml(WriteModel("process_noise:\n  a_dist: 3.0\n  a_dist: 0.3\n"), LagrVehicle());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.column(), "process_noise.a_dist");
    EXPECT_EQ(e.line(), 3);
  }
  EXPECT_THROW(ReadModelYaml(WriteModel("tire: {C1: 0.6}\ntire: {C1: 0.7}\n"), LagrVehicle()),
               InputError);
}

// A file whose YAML parses but whose structure is another (a scalar where a mapping belongs):
// an error naming the file, not yaml-cpp's exception (found by fuzz/config_fuzzer).
TEST(YamlConfig, AnUnexpectedStructureIsAnInputError) {
  std::string text = testing::kLagrVehicleYaml;
  text = text.substr(0, text.find("sensors:")) + "sensors: just text\n";
  const std::string dir = testing::FreshDirectory("structure");
  testing::WriteText(dir, "vehicle.yaml", text);
  std::vector<std::string> warnings;
  EXPECT_THROW(ReadVehicleYaml(dir + "/vehicle.yaml", &warnings), InputError);
}

TEST(YamlConfig, UnknownEffectNameIsAnErrorNamingItsLine) {
  try {
    ReadModelYaml(WriteModel("tire: {C1: 0.6}\neffects: [quadratic_drag, warp_drive]\n"),
                  LagrVehicle());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.column(), "effects");
    EXPECT_EQ(e.value(), "warp_drive");
  }
  // corrugation exists only in the simulator: outside the model catalogue on purpose.
  EXPECT_THROW(ReadModelYaml(WriteModel("effects: [corrugation]\n"), LagrVehicle()), InputError);
  // Sinkage acts on windows of the drive, which the model must give.
  EXPECT_THROW(ReadModelYaml(WriteModel("effects: [sinkage_resistance]\n"), LagrVehicle()),
               InputError);
  EXPECT_THROW(
      ReadModelYaml(WriteModel("effect_windows: [{effect: quadratic_drag, from: 1, to: 2}]\n"),
                    LagrVehicle()),
      InputError);
  EXPECT_THROW(
      ReadModelYaml(WriteModel("effects: [sinkage_resistance]\n"
                               "effect_windows: [{effect: sinkage_resistance, from: 5}]\n"),
                    LagrVehicle()),
      InputError);
  const ModelConfig sinkage = ReadModelYaml(
      WriteModel("effects: [sinkage_resistance]\n"
                 "effect_windows: [{effect: sinkage_resistance, from: 21.5, to: 38.25}]\n"),
      LagrVehicle());
  ASSERT_EQ(sinkage.effect_windows.size(), 1u);
  EXPECT_EQ(sinkage.effect_windows[0].effect, "sinkage_resistance");
  EXPECT_DOUBLE_EQ(sinkage.effect_windows[0].t_start_s, 21.5);
  EXPECT_DOUBLE_EQ(sinkage.effect_windows[0].t_end_s, 38.25);
  // So does a terrain change (the changed terrain's times).
  EXPECT_THROW(ReadModelYaml(WriteModel("effects: [terrain_change]\n"), LagrVehicle()), InputError);
  const ModelConfig change =
      ReadModelYaml(WriteModel("effects: [terrain_change]\n"
                               "effect_windows: [{effect: terrain_change, from: 31, to: 87}]\n"),
                    LagrVehicle());
  EXPECT_TRUE(change.InEffectWindow("terrain_change", 40.0));
  EXPECT_FALSE(change.InEffectWindow("terrain_change", 20.0));
}

// A count (the samples the offsets are averaged over, the intervals of a lasting run) is a whole
// number: 2.5 is an error naming its key and line, not 2.
TEST(YamlConfig, ACountThatIsNotAWholeNumberIsAnErrorNamingIt) {
  try {
    ReadModelYaml(WriteModel("tire: {C1: 0.6}\nslip_persistence:\n  lasting_intervals: 2.5\n"),
                  LagrVehicle());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.column(), "slip_persistence.lasting_intervals");
    EXPECT_EQ(e.line(), 3);
  }
  EXPECT_THROW(ReadModelYaml(WriteModel("offsets: {init_samples: 1e12}\n"), LagrVehicle()),
               InputError);
  const ModelConfig m = ReadModelYaml(WriteModel("offsets: {init_samples: 250}\nslip_persistence: "
                                                 "{lasting_intervals: 4.0}\n"),
                                      LagrVehicle());
  EXPECT_EQ(m.offset_init_samples, 250);
  EXPECT_EQ(m.slip_persistence.lasting_intervals, 4);
}

TEST(YamlConfig, InvalidModelValueIsRejected) {
  EXPECT_THROW(ReadModelYaml(WriteModel("weak_constraints: {decay_alpha: 1.5}\n"), LagrVehicle()),
               InputError);
  EXPECT_THROW(ReadModelYaml(WriteModel("tire: {C1: -1}\n"), LagrVehicle()), InputError);
  EXPECT_THROW(
      ReadModelYaml(WriteModel("process_noise: {attitude_error_walk: -1}\n"), LagrVehicle()),
      InputError);
  EXPECT_THROW(ReadModelYaml(WriteModel("slip_persistence: {interval: -0.3}\n"), LagrVehicle()),
               InputError);
  EXPECT_THROW(ReadModelYaml(WriteModel("slip_persistence: {sd: 0}\n"), LagrVehicle()), InputError);
  // Off, its other fields are not read.
  EXPECT_NO_THROW(
      ReadModelYaml(WriteModel("slip_persistence: {interval: 0, sd: 0}\n"), LagrVehicle()));
  EXPECT_THROW(ReadModelYaml(WriteModel("weak_constraints: {oppose_motion_cauchy_scale: -1}\n"),
                             LagrVehicle()),
               InputError);
  EXPECT_THROW(
      ReadModelYaml(WriteModel("weak_constraints: {still_smoothing: -0.1}\n"), LagrVehicle()),
      InputError);
  EXPECT_THROW(
      ReadModelYaml(WriteModel("calibration: {wheel_radius_scale_left: 0}\n"), LagrVehicle()),
      InputError);
  EXPECT_THROW(ReadModelYaml(WriteModel("calibration: {imu_time_offset: 1.5}\n"), LagrVehicle()),
               InputError);
  EXPECT_THROW(ReadModelYaml(WriteModel("calibration: {imu_mounting_pitch: 0.3}\n"), LagrVehicle()),
               InputError);
  EXPECT_THROW(
      ReadModelYaml(WriteModel("calibration: {wheels_time_offset: -1.2}\n"), LagrVehicle()),
      InputError);
}

TEST(YamlConfig, WrittenModelReadsBackTheSame) {
  ModelConfig m = DefaultModelConfig(LagrVehicle());
  m.tire.C2 = -0.02;
  m.weak_constraints.decay_alpha = 0.7;
  m.weak_constraints.oppose_motion_cauchy_scale_mps2 = 0.0;
  m.weak_constraints.still_smoothing_s = 0.25;
  m.effects = {"quadratic_drag", "imu_mounting_pitch"};
  m.calibration.wheel_radius_scale_right = 0.97;
  m.calibration.track_width_m = 0.81;
  m.calibration.imu_time_offset_s = -0.035;
  m.calibration.wheels_time_offset_s = 0.36;
  m.calibration.imu_mounting_pitch_rad = 0.021;
  m.process.attitude_error_walk_s = 45.0;
  m.slip_persistence.interval_s = 0.45;
  m.slip_persistence.sd_mps = 0.007;
  m.slip_persistence.gate_sd = 2.5;
  m.slip_persistence.smoothing_s = 0.15;
  m.slip_persistence.min_rim_speed_mps = 0.05;
  m.slip_persistence.max_rim_acceleration_mps2 = 0.02;
  m.slip_persistence.lasting_intervals = 4;
  m.slip_persistence.max_lasting_error_mps2 = 0.12;
  m.gnss_heading_from_course = false;
  std::ostringstream out;
  WriteModelYaml(m, out);
  const ModelConfig back = ReadModelYaml(WriteModel(out.str()), LagrVehicle());
  EXPECT_DOUBLE_EQ(back.tire.C2, -0.02);
  EXPECT_DOUBLE_EQ(back.weak_constraints.decay_alpha, 0.7);
  EXPECT_DOUBLE_EQ(back.weak_constraints.still_smoothing_s, 0.25);
  EXPECT_EQ(back.effects, m.effects);
  EXPECT_EQ(back.offset_init_samples, m.offset_init_samples);
  EXPECT_DOUBLE_EQ(back.calibration.wheel_radius_scale_left, 1.0);
  EXPECT_DOUBLE_EQ(back.calibration.wheel_radius_scale_right, 0.97);
  EXPECT_DOUBLE_EQ(back.calibration.track_width_m, 0.81);
  EXPECT_DOUBLE_EQ(back.calibration.imu_time_offset_s, -0.035);
  EXPECT_DOUBLE_EQ(back.calibration.wheels_time_offset_s, 0.36);
  EXPECT_DOUBLE_EQ(back.calibration.imu_mounting_pitch_rad, 0.021);
  EXPECT_DOUBLE_EQ(back.process.attitude_error_walk_s, 45.0);
  EXPECT_DOUBLE_EQ(back.slip_persistence.interval_s, 0.45);
  EXPECT_DOUBLE_EQ(back.slip_persistence.sd_mps, 0.007);
  EXPECT_DOUBLE_EQ(back.slip_persistence.gate_sd, 2.5);
  EXPECT_DOUBLE_EQ(back.slip_persistence.smoothing_s, 0.15);
  EXPECT_DOUBLE_EQ(back.slip_persistence.min_rim_speed_mps, 0.05);
  EXPECT_DOUBLE_EQ(back.slip_persistence.max_rim_acceleration_mps2, 0.02);
  EXPECT_EQ(back.slip_persistence.lasting_intervals, 4);
  EXPECT_DOUBLE_EQ(back.slip_persistence.max_lasting_error_mps2, 0.12);
  EXPECT_FALSE(back.gnss_heading_from_course);
}

TEST(YamlConfig, ASwitchThatIsNotTrueOrFalseIsAnErrorNamingIt) {
  EXPECT_TRUE(
      ReadModelYaml(WriteModel("tire: {C1: 0.6}\n"), LagrVehicle()).gnss_heading_from_course);
  try {
    ReadModelYaml(WriteModel("tire: {C1: 0.6}\ngnss_heading_from_course: 0.5\n"), LagrVehicle());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.column(), "gnss_heading_from_course");
    EXPECT_EQ(e.line(), 2);
  }
}

TEST(YamlConfig, UnknownVehicleKeyIsAWarningAndMissingSensorsAreDefaulted) {
  const std::string dir = testing::FreshDirectory("vehicle");
  testing::WriteText(
      dir, "vehicle.yaml",
      "type: skid_steer\nmass: 50\nyaw_inertia: 3\nwheel_radius: 0.1\n"
      "track_width: 0.5\ncg_height: 0.2\ncolour: red\n"
      "tire: {C1: 0.8, At: 20, C2: 0.05}\nrolling: {R1: 0.03, A_roll: 20, R2: 0.01}\n");
  std::vector<std::string> warnings;
  const Vehicle v = ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
  EXPECT_EQ(v.type, VehicleType::kSkidSteer);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("colour"), std::string::npos);
  EXPECT_EQ(v.defaulted_keys.size(), 3u);
}

// The LAGR's vehicle.yaml with `from` replaced by `to`, read.
Vehicle LagrVehicleWith(const std::string& from, const std::string& to) {
  std::string yaml = testing::kLagrVehicleYaml;
  yaml.replace(yaml.find(from), from.size(), to);
  const std::string dir = testing::FreshDirectory("vehicle");
  testing::WriteText(dir, "vehicle.yaml", yaml);
  std::vector<std::string> warnings;
  return ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
}

TEST(YamlConfig, NonPositiveDimensionIsRejected) {
  EXPECT_THROW(LagrVehicleWith("wheel_radius: 0.25", "wheel_radius: 0.0"), InputError);
}

// `sd_omega: 0` weighed the encoders as exact; the filter's covariance collapsed and the
// smoother printed 109 k lines of solver dumps.
TEST(YamlConfig, ASensorSdOfZeroIsAnErrorNamingIt) {
  try {
    LagrVehicleWith("sd_omega: 0.05", "sd_omega: 0");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.column(), "sensors.wheels.sd_omega");
    EXPECT_NE(std::string(e.what()).find("must be positive"), std::string::npos);
  }
}

// The law's optional uncertainty (tire_sd, rolling_sd, law_samples: extensions of vehicle.yaml):
// read, written back only when stated, into the model by default; a bad value names its key.
TEST(YamlConfig, TheLawsStatedUncertaintyReadsWritesAndIsChecked) {
  const std::string dir = testing::FreshDirectory("vehicle");
  testing::WriteText(dir, "vehicle.yaml",
                     std::string(testing::kLagrVehicleYaml) +
                         "tire_sd: {C1: 0.1, At: 5}\nrolling_sd: {R1: 0.02, R2: 0.007}\n");
  std::vector<std::string> warnings;
  const Vehicle v = ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
  EXPECT_TRUE(warnings.empty());
  EXPECT_DOUBLE_EQ(v.tire_sd.C1, 0.1);
  EXPECT_DOUBLE_EQ(v.tire_sd.At, 5.0);
  EXPECT_DOUBLE_EQ(v.tire_sd.C2, 0.0);  // not stated: exact
  EXPECT_DOUBLE_EQ(v.rolling_sd.R2, 0.007);
  const ModelConfig m = DefaultModelConfig(v);
  EXPECT_DOUBLE_EQ(m.rolling_sd.R1, 0.02);
  std::ostringstream out;
  WriteVehicleYaml(v, out);
  EXPECT_NE(out.str().find("tire_sd"), std::string::npos);
  std::ostringstream plain;
  WriteVehicleYaml(LagrVehicle(), plain);
  EXPECT_EQ(plain.str().find("tire_sd"), std::string::npos);
  // The model file may state or override it.
  EXPECT_DOUBLE_EQ(ReadModelYaml(WriteModel("rolling_sd: {R1: 0.05}\n"), v).rolling_sd.R1, 0.05);
  // The slope's sd on a log scale (model file only), in [0, 2], and written back.
  const ModelConfig slope = ReadModelYaml(WriteModel("tire_sd: {slip_stiffness: 0.7}\n"), v);
  EXPECT_DOUBLE_EQ(slope.tire_slip_stiffness_relative_sd, 0.7);
  std::ostringstream slope_out;
  WriteModelYaml(slope, slope_out);
  EXPECT_DOUBLE_EQ(ReadModelYaml(WriteModel(slope_out.str()), v).tire_slip_stiffness_relative_sd,
                   0.7);
  try {
    ReadModelYaml(WriteModel("tire_sd: {slip_stiffness: 2.5}\n"), v);
    FAIL() << "a slope sd of 2.5 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tire_sd.slip_stiffness"), std::string::npos) << e.what();
  }
  testing::WriteText(dir, "vehicle.yaml",
                     std::string(testing::kLagrVehicleYaml) + "tire_sd: {C1: -0.1}\n");
  try {
    ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
    FAIL() << "a negative sd was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tire_sd.C1"), std::string::npos) << e.what();
  }
  // law_samples: every coefficient of each soil, written back, a missing one named.
  testing::WriteText(dir, "vehicle.yaml",
                     std::string(testing::kLagrVehicleYaml) +
                         "law_samples:\n  - {C1: 0.5, At: 10, C2: 0.08, R1: 0.07, A_roll: 15, "
                         "R2: 0.02}\n  - {C1: 0.6, At: 15, C2: 0.05, R1: 0.04, A_roll: 20, "
                         "R2: 0.01}\n");
  const Vehicle with_samples = ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
  ASSERT_EQ(with_samples.law_samples.size(), 2u);
  EXPECT_DOUBLE_EQ(with_samples.law_samples[1].rolling.A_roll, 20.0);
  EXPECT_EQ(DefaultModelConfig(with_samples).law_samples.size(), 2u);
  std::ostringstream samples_out;
  WriteVehicleYaml(with_samples, samples_out);
  testing::WriteText(dir, "vehicle.yaml", samples_out.str());
  EXPECT_DOUBLE_EQ(ReadVehicleYaml(dir + "/vehicle.yaml", &warnings).law_samples[0].tire.C2, 0.08);
  testing::WriteText(dir, "vehicle.yaml",
                     std::string(testing::kLagrVehicleYaml) +
                         "law_samples:\n  - {C1: 0.5, At: 10, C2: 0.08, R1: 0.07, A_roll: 15}\n");
  try {
    ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
    FAIL() << "a soil without R2 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("law_samples[0].R2"), std::string::npos) << e.what();
  }
  std::string error;
  ModelConfig bad = m;
  bad.tire_sd.At = -1.0;
  EXPECT_FALSE(bad.IsValid(&error));
  EXPECT_NE(error.find("tire_sd"), std::string::npos);
  ModelConfig bad_soil = DefaultModelConfig(with_samples);
  EXPECT_TRUE(bad_soil.IsValid(&error)) << error;
  bad_soil.law_samples[1].tire.At = 0.0;
  EXPECT_FALSE(bad_soil.IsValid(&error));
  EXPECT_NE(error.find("law_samples[1]"), std::string::npos) << error;
}

TEST(YamlConfig, SyntaxErrorNamesTheLine) {
  const std::string dir = testing::FreshDirectory("vehicle");
  testing::WriteText(dir, "vehicle.yaml", "type: skid_steer\nmass: [1, 2\n");
  std::vector<std::string> warnings;
  try {
    ReadVehicleYaml(dir + "/vehicle.yaml", &warnings);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_GT(e.line(), 0);
  }
}

}  // namespace
}  // namespace slipgraph
