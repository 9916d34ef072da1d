// In-memory drive log: every file of shared/log-format.md as a vector of samples, SI units, the
// log's frames (REP-103 body, ENU world). Missing optional values are NaN. A stream whose file is
// absent has an empty vector and is not listed in `present_files`.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "model/model_config.h"
#include "model/vehicle.h"

namespace slipgraph {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxWheels = 6;

enum class Side { kLeft, kRight };
const char* SideName(Side side);

struct ImuSample {
  double t = 0.0;
  double ax = 0.0, ay = 0.0, az = 0.0;  // specific force, body frame, m/s^2 (gravity included)
  double gx = 0.0, gy = 0.0, gz = 0.0;  // angular rate, body frame, rad/s
};

struct WheelSample {
  double t = 0.0;
  // Angular velocity per wheel in WheelNames(vehicle.type) order, rad/s, positive forward.
  std::array<double, kMaxWheels> omega_radps{};
};

struct AttitudeSample {
  double t = 0.0;
  double roll = 0.0, pitch = 0.0, yaw = 0.0;  // rad, REP-103, Z-Y-X
  double sd_roll = kMissing, sd_pitch = kMissing, sd_yaw = kMissing;
};

struct GpsSample {
  double t = 0.0;
  double x = 0.0, y = 0.0, z = 0.0;     // local ENU, m
  double vx = 0.0, vy = 0.0, vz = 0.0;  // ENU, m/s
  double sd_xy = kMissing, sd_z = kMissing, sd_v = kMissing;
};

// A fix's velocity sd: its own when the row states a positive one, else `stated_mps` (the
// model's or vehicle.yaml's).
inline double GnssVelocitySd(const GpsSample& fix, double stated_mps) {
  return std::isfinite(fix.sd_v) && fix.sd_v > 0.0 ? fix.sd_v : stated_mps;
}

struct PoseSample {
  double t = 0.0;
  double x = 0.0, y = 0.0, z = 0.0;
  double roll = 0.0, pitch = 0.0, yaw = 0.0;
  double sd_x = kMissing, sd_y = kMissing, sd_yaw = kMissing;
};

struct ArticulationSample {
  double t = 0.0;
  Side side = Side::kLeft;
  double dz_mid = 0.0;    // middle minus rear wheel contact elevation, m
  double dz_front = 0.0;  // front minus rear wheel contact elevation, m
};

struct RangeSample {
  double t = 0.0;
  Side side = Side::kLeft;
  double d = 0.0;   // horizontal distance ahead of the rear wheel contact point, m
  double dz = 0.0;  // elevation minus the rear wheel contact point's, m
};

struct CommandSample {
  double t = 0.0;
  double v = 0.0;      // commanded forward speed, m/s
  double omega = 0.0;  // commanded yaw rate, rad/s
};

struct TruthSample {
  double t = 0.0;
  double x = 0.0, y = 0.0, z = 0.0;
  double roll = 0.0, pitch = 0.0, yaw = 0.0;
  double vx = 0.0, vy = 0.0;  // body-frame velocity, m/s
  double yaw_rate = 0.0;
  double a_dist = kMissing;                  // disturbance acceleration along body x, m/s^2
  double immobilized = kMissing;             // 0 or 1
  std::array<double, kMaxWheels> slip{};     // per wheel, NaN when absent
  std::array<double, kMaxWheels> sinkage{};  // per wheel, m, NaN when absent
};

struct Event {
  double t_start = 0.0;
  double t_end = 0.0;
  std::string label;
};

struct DriveLog {
  std::string directory;
  Vehicle vehicle;
  std::vector<ImuSample> imu;
  std::vector<WheelSample> wheels;
  std::vector<AttitudeSample> attitude;
  std::vector<GpsSample> gps;
  std::vector<PoseSample> pose;
  std::vector<ArticulationSample> articulation;
  std::vector<RangeSample> range;
  std::vector<CommandSample> commands;
  std::vector<TruthSample> truth;
  std::vector<Event> events;
  std::vector<std::string> present_files;  // file names read, e.g. "gps.csv"
  std::vector<std::string> warnings;       // everything skipped or defaulted, one line each

  bool Has(const std::string& file_name) const;
  int wheel_count() const { return static_cast<int>(WheelNames(vehicle.type).size()); }
};

// The samples of every stream with t in [t_begin, t_end), and the events that overlap it
// (clipped to it); vehicle, files and warnings as the log's. For cross-validation: fit on one
// part of a drive, score on another.
DriveLog SliceLog(const DriveLog& log, double t_begin, double t_end);

// The model file's calibration (ModelConfig::calibration) applied to the log: each wheel's speed
// scaled by its side's radius scale (the estimators then read it as the speed of a wheel of
// vehicle.yaml's radius), the vehicle's track set to the effective track when one is given, the
// IMU's stamps (imu.csv; attitude.csv keeps its own) moved earlier by the IMU's time offset, the
// encoders' (wheels.csv) by theirs, and the IMU's axes rotated back by its mounting pitch.
void ApplyCalibration(const ModelConfig& model, DriveLog* log);
// The IMU's stamps (imu.csv) moved earlier by offset_s: what an IMU clock late by offset_s needs.
void MoveImuStampsBack(double offset_s, DriveLog* log);
// The encoders' stamps (wheels.csv) moved earlier by offset_s: what encoders late by offset_s
// need.
void MoveWheelStampsBack(double offset_s, DriveLog* log);
// The IMU's accelerometer and gyro (imu.csv) rotated back by pitch_rad about body y: what an IMU
// mounted pitched nose-down by pitch_rad needs (attitude.csv is left as the body's).
void RotateImuAxesBack(double pitch_rad, DriveLog* log);

}  // namespace slipgraph
