#include "io/drive_log.h"

#include <algorithm>
#include <cmath>

namespace slipgraph {

const char* SideName(Side side) { return side == Side::kLeft ? "left" : "right"; }

bool DriveLog::Has(const std::string& file_name) const {
  return std::find(present_files.begin(), present_files.end(), file_name) != present_files.end();
}

namespace {

template <typename Sample>
std::vector<Sample> InRange(const std::vector<Sample>& samples, double t_begin, double t_end) {
  std::vector<Sample> out;
  for (const Sample& s : samples) {
    if (s.t >= t_begin && s.t < t_end) out.push_back(s);
  }
  return out;
}

}  // namespace

DriveLog SliceLog(const DriveLog& log, double t_begin, double t_end) {
  DriveLog out;
  out.directory = log.directory;
  out.vehicle = log.vehicle;
  out.present_files = log.present_files;
  out.warnings = log.warnings;
  out.imu = InRange(log.imu, t_begin, t_end);
  out.wheels = InRange(log.wheels, t_begin, t_end);
  out.attitude = InRange(log.attitude, t_begin, t_end);
  out.gps = InRange(log.gps, t_begin, t_end);
  out.pose = InRange(log.pose, t_begin, t_end);
  out.articulation = InRange(log.articulation, t_begin, t_end);
  out.range = InRange(log.range, t_begin, t_end);
  out.commands = InRange(log.commands, t_begin, t_end);
  out.truth = InRange(log.truth, t_begin, t_end);
  for (Event e : log.events) {
    if (e.t_end <= t_begin || e.t_start >= t_end) continue;
    e.t_start = std::max(e.t_start, t_begin);
    e.t_end = std::min(e.t_end, t_end);
    out.events.push_back(e);
  }
  return out;
}

void ApplyCalibration(const ModelConfig& model, DriveLog* log) {
  const CalibrationConfig& c = model.calibration;
  if (c.wheel_radius_scale_left != 1.0 || c.wheel_radius_scale_right != 1.0) {
    const std::vector<std::string>& names = WheelNames(log->vehicle.type);
    for (WheelSample& w : log->wheels) {
      for (size_t i = 0; i < names.size(); ++i) {
        w.omega_radps[i] *=
            WheelSide(names[i]) > 0 ? c.wheel_radius_scale_left : c.wheel_radius_scale_right;
      }
    }
  }
  if (c.track_width_m > 0.0) log->vehicle.track_width_m = c.track_width_m;
  if (c.imu_time_offset_s != 0.0) MoveImuStampsBack(c.imu_time_offset_s, log);
  if (c.wheels_time_offset_s != 0.0) MoveWheelStampsBack(c.wheels_time_offset_s, log);
  if (c.imu_mounting_pitch_rad != 0.0) RotateImuAxesBack(c.imu_mounting_pitch_rad, log);
}

void MoveImuStampsBack(double offset_s, DriveLog* log) {
  for (ImuSample& s : log->imu) s.t -= offset_s;
}

void MoveWheelStampsBack(double offset_s, DriveLog* log) {
  for (WheelSample& w : log->wheels) w.t -= offset_s;
}

void RotateImuAxesBack(double pitch_rad, DriveLog* log) {
  const double c = std::cos(pitch_rad), s = std::sin(pitch_rad);
  for (ImuSample& imu : log->imu) {
    const double fx = imu.ax * c + imu.az * s, fz = -imu.ax * s + imu.az * c;
    const double wx = imu.gx * c + imu.gz * s, wz = -imu.gx * s + imu.gz * c;
    imu.ax = fx, imu.az = fz, imu.gx = wx, imu.gz = wz;
  }
}

}  // namespace slipgraph
