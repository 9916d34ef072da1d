// Nominal vehicle description: what the user believes about the robot (vehicle.yaml of a log,
// see shared/log-format.md). Plain data; parsing lives in io/yaml_config.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace slipgraph {

enum class VehicleType { kDiffDriveCastor, kSkidSteer, kRockerBogie6 };

// "diff_drive_castor" | "skid_steer" | "rocker_bogie6".
const char* VehicleTypeName(VehicleType type);
// Returns false when `name` is not a known vehicle type.
bool ParseVehicleType(const std::string& name, VehicleType* type);

// Column names of wheels.csv for a vehicle type, in the order of the format document.
const std::vector<std::string>& WheelNames(VehicleType type);
// +1 for a wheel on the left side, -1 for the right side (body y is left).
int WheelSide(const std::string& wheel_name);

// Ward & Iagnemma eq. (8): F = N (sign(v_rel) C1 (1 - exp(-At |v_rel|)) + C2 v_rel).
struct TireParams {
  double C1 = 0.8;   // maximum traction coefficient, dimensionless
  double At = 20.0;  // slope of the traction curve at small relative velocity, s/m
  double C2 = 0.05;  // slope at large relative velocity, s/m (may be negative)
};

// The law's slope at small slip scaled: At and C2 times `scale`, so that the traction at
// relative velocity v_rel is the unscaled law's at scale v_rel (the slip a force needs divided by
// scale).
inline void ScaleSlipStiffness(double scale, TireParams* tire) {
  tire->At *= scale;
  tire->C2 *= scale;
}

// The two scales at which a slope uncertain by `relative_sd` is tried (a consider covariance:
// the mean of the two squared shifts): exp(-sd) and exp(+sd), one sd each way on a log scale, so
// that a slope half as steep and one twice as steep are equally likely (sd 0.69).
inline std::array<double, 2> SlipStiffnessSdScales(double relative_sd) {
  return {std::exp(-relative_sd), std::exp(relative_sd)};
}

// Ward & Iagnemma eq. (9): F = -sign(v) N (R1 (1 - exp(-A_roll |v|)) + R2 |v|).
struct RollingParams {
  double R1 = 0.03;      // static rolling-resistance coefficient, dimensionless
  double A_roll = 20.0;  // smoothing of the static part near zero speed, s/m
  double R2 = 0.01;      // viscous rolling-resistance coefficient, s/m
};

// One soil's tire and rolling law (Vehicle::law_samples).
struct LawSample {
  TireParams tire;
  RollingParams rolling;
};

// Nominal sensor noise, standard deviations (per sample).
struct SensorNoise {
  double imu_sd_accel_mps2 = 0.05;
  double imu_sd_gyro_radps = 0.005;
  double wheels_sd_omega_radps = 0.05;
  double gps_sd_xy_m = 0.5;
  double gps_sd_v_mps = 0.1;
};

struct Vehicle {
  std::string name;  // free text
  VehicleType type = VehicleType::kDiffDriveCastor;
  double mass_kg = 0.0;           // m
  double yaw_inertia_kgm2 = 0.0;  // J, about body z
  double wheel_radius_m = 0.0;    // r
  double track_width_m = 0.0;     // c, left-right wheel centre distance
  double cg_to_front_m = 0.0;     // a
  double cg_to_rear_m = 0.0;      // b
  double cg_height_m = 0.0;       // h
  double axle_spacing_m = 0.0;    // A, rocker_bogie6 only
  TireParams tire;
  RollingParams rolling;
  // Optional (vehicle.yaml `tire_sd`, `rolling_sd`, an extension of the format): the sd of those
  // coefficients when they are a fit the terrain may not follow; 0 when not stated.
  TireParams tire_sd{0.0, 0.0, 0.0};
  RollingParams rolling_sd{0.0, 0.0, 0.0};
  // Optional (vehicle.yaml `law_samples`): the laws of the soils the law above was fitted over;
  // their spread around it, correlations included, is the law's uncertainty (used instead of
  // the sd when there are two or more).
  std::vector<LawSample> law_samples;
  SensorNoise sensors;
  // Sensor sections that vehicle.yaml did not give (defaults above were used), e.g. "sensors.gps".
  std::vector<std::string> defaulted_keys;
};

}  // namespace slipgraph
