// A simulation scenario: the vehicle the user believes in (written to vehicle.yaml), the true
// course, the driving commands, hold-back events, sensors and the effects switched on.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "model/vehicle.h"
#include "sim/effects.h"
#include "sim/terrain.h"

namespace slipgraph {
namespace sim {

// Drive toward (v, yaw rate) for duration_s; the command ramps at the actuation limits.
struct CommandSegment {
  double duration_s = 1.0;
  double v_mps = 0.0;
  double yaw_rate_radps = 0.0;
};

// Someone holds the robot back with a spring scale (a stiff, damped tether anchored where the
// robot is at t_start_s) until t_end_s. The tether only pulls backwards.
struct HoldBack {
  double t_start_s = 0.0;
  double t_end_s = 0.0;
};

// Wheel-speed controllers and drive limits (diff_drive_castor).
struct Actuation {
  double accel_limit_mps2 = 0.8;        // command ramp
  double yaw_accel_limit_radps2 = 2.0;  // command ramp
  double torque_limit_nm = 60.0;        // per driven wheel motor
  double wheel_inertia_kgm2 = 0.4;      // wheel + reflected motor inertia
  double kp_nm_per_radps = 15.0;        // PI wheel-speed controller
  double ki_nm_per_rad = 60.0;
  double tether_stiffness_npm =
      10000.0;  // a person leaning on a spring scale: stops the robot in ~0.2 s
  double tether_damping_nspm = 2000.0;  // about critical for the LAGR mass
};

// Sensor errors of the mismatch suites (docs/mismatch.md), zero in the matched ones: an AHRS
// whose roll and pitch carry a slowly varying error, chassis vibration in the accelerometer
// growing with speed, GNSS velocity averaged over the interval since the previous fix.
struct SensorMismatch {
  double attitude_error_sd_rad = 0.0;  // Gauss-Markov error on roll and pitch
  double attitude_error_tau_s = 30.0;
  double vibration_sd_mps2_per_mps = 0.0;  // sd of the vibration at 1 m/s, along x and z
  double vibration_hz = 12.0;              // the chassis' resonance
  double vibration_damping = 0.05;         // its damping ratio
  bool gps_velocity_interval_mean = false;
};

struct SensorSpec {
  double imu_rate_hz = 100.0;
  double wheel_rate_hz = 100.0;
  double gps_rate_hz = 1.0;         // 0: no gps.csv
  double attitude_rate_hz = 100.0;  // 0: no attitude.csv
  double pose_rate_hz = 0.0;        // 0: no pose.csv
  double command_rate_hz = 10.0;    // 0: no commands.csv
  double truth_rate_hz = 100.0;
  int encoder_counts_per_rev = 4096;  // 0: no quantization
  double sd_accel_mps2 = 0.05;
  double sd_gyro_radps = 0.005;
  double accel_offset_max_mps2 = 0.1;  // constant offset c_ax ~ U(-max, max)
  double gyro_offset_max_radps = 0.01;
  double accel_bias_sd_mps2 = 0.02;  // walking bias, Gauss-Markov
  double accel_bias_tau_s = 300.0;
  double gyro_bias_sd_radps = 0.002;
  double gyro_bias_tau_s = 300.0;
  double sd_omega_radps = 0.02;  // encoder speed noise on top of quantization
  double gps_sd_xy_m = 0.5;
  double gps_sd_z_m = 1.0;
  double gps_sd_v_mps = 0.1;
  double attitude_sd_rad = 0.002;
  double attitude_sd_yaw_rad = 0.01;
  double pose_sd_xy_m = 0.02;
  double pose_sd_yaw_rad = 0.005;
  SensorMismatch mismatch;
};

// Vehicle-side truth of the mismatch suites (docs/mismatch.md; the soils are the patches'
// TerrainType::peaked or track_soil): how far the tires roll before their slip settles, and how
// their rolling radius shrinks with load; the tracks' contact and the soil's variation under
// them. Inert when the patches have no such soil.
struct VehicleMismatch {
  double relaxation_length_m = 0.2;
  double radius_load_sensitivity = 0.0;  // r_eff = r (1 - k (N / N_static - 1))
  // The tracked robot (TerrainType::track_soil): its contact, and the soil's variation along
  // the path under each track (each track's strength and shear modulus scaled by exp(sd z), z a
  // unit Gauss-Markov process in distance with this correlation length).
  TrackGeometry tracks;
  double track_soil_variation_sd = 0.0;
  double track_soil_correlation_m = 2.0;  // > 0
};

// The articulated 6-wheel rover of Wilcox: per-side terrain profiles, sinkage, slip, and the
// articulation and look-ahead ranging sensors.
struct RockerSpec {
  double roughness_rms_m = 0.01;  // RMS of each side's synthetic terrain profile y(x)
  double slip_mean = 0.2;         // true slip: advance = rim motion x (1 - slip)
  double slip_sd = 0.02;          // sd of the slip's variation (each cycle's own, or correlated)
  // Slip against slope (Wilcox Sec. 5: odometry over-estimates uphill, under-estimates downhill):
  // slip = slip_mean + slip_per_slope x dz/dx of the course's hills under the rover's middle
  // wheels, clamped to [0, 0.9]. The hills (Course::hills) lift both sides' profiles.
  double slip_per_slope = 0.0;
  double cycle_rate_hz = 1.0;          // articulation and range sampling
  double articulation_sd_m = 0.00004;  // 0.04 mm (Wilcox Sec. 3)
  double range_sd_m = 0.002;           // 2 mm
  double range_first_m = 0.02;         // first sensed point ahead of the front wheel
  double range_spacing_m = 0.02;       // spacing of sensed points
  int range_points = 30;               // per side and cycle
  double base_sinkage_m = 0.003;       // sinkage everywhere
  double soft_sinkage_m = 0.015;       // extra sinkage at the centre of soft patches
  double soft_patch_every_m = 2.0;     // a soft patch (raised cosine, 0.6 m long) this often
  double left_extra_sinkage_m = 0.0;   // > 0: the left side sinks more (breaks the L/R check)
  double contact_divisor = 3.0;        // each wheel averages the terrain over radius / this
  // The mismatch suite wilcoxm (docs/mismatch.md); inert at these values. slip_correlation_m > 0:
  // the slip's variation (slip_sd) is a Gauss-Markov process in distance, else i.i.d. per cycle;
  // the wheels dig in at a soft patch (more slip at its centre); the middle and rear wheels
  // deepen the front's rut by a share of its sinkage; the ranging sensor's pitch is off its
  // calibration (each point's elevation off by its distance x tan(error)).
  double slip_correlation_m = 0.0;
  double soft_extra_slip = 0.0;
  double middle_extra_sinkage = 0.0;
  double rear_extra_sinkage = 0.0;
  double range_pitch_error_rad = 0.0;
};

// What a user-supplied extra force may depend on (Scenario::extra_force_n).
struct ExtraForceInputs {
  double t_s = 0.0;
  double distance_m = 0.0;  // along the course
  double v_mps = 0.0;       // body x velocity
  double yaw_rate_radps = 0.0;
  double grade_rad = 0.0;  // uphill positive
  double cross_slope_rad = 0.0;
  double mass_kg = 0.0;
};

struct Scenario {
  std::string name;
  Vehicle vehicle;  // nominal: what vehicle.yaml says; the truth may differ through effects
  Course course;
  double rest_start_s = 3.0;  // at rest before the first command (IMU offset initialisation)
  std::vector<CommandSegment> commands;
  std::vector<HoldBack> holdbacks;
  Actuation actuation;
  SensorSpec sensors;
  EffectSet effects;
  RockerSpec rocker;  // rocker_bogie6 only
  VehicleMismatch mismatch;
  // A force along body x (N) the catalogue does not have, for testing a user's own effect
  // (docs/adding-an-effect.md); differential-drive vehicles only. Unset: none.
  std::function<double(const ExtraForceInputs&)> extra_force_n;
  double sim_step_s = 0.0005;  // internal integration step

  double duration_s() const {
    double total = rest_start_s;
    for (const CommandSegment& c : commands) total += c.duration_s;
    return total;
  }
};

}  // namespace sim
}  // namespace slipgraph
