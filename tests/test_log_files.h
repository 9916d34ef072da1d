// Writes small, valid drive logs file by file (independently of io/log_writer), so the reader's
// tests can corrupt one thing at a time.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace slipgraph {
namespace testing {

inline const char* kLagrVehicleYaml = R"(name: lagr
type: diff_drive_castor
mass: 117.0
yaw_inertia: 15.0
wheel_radius: 0.25
track_width: 0.55
cg_to_front: 0.35
cg_to_rear: 0.55
cg_height: 0.30
tire:    {C1: 0.8, At: 20.0, C2: 0.05}
rolling: {R1: 0.03, A_roll: 20.0, R2: 0.01}
sensors:
  imu:    {sd_accel: 0.05, sd_gyro: 0.005}
  wheels: {sd_omega: 0.05}
  gps:    {sd_xy: 0.5, sd_v: 0.1}
)";

// A fresh directory under the test temp dir, unique per test.
inline std::string FreshDirectory(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) /
      (std::string(info->test_suite_name()) + "_" + info->name() + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline void WriteText(const std::string& directory, const std::string& file,
                      const std::string& text) {
  std::ofstream(std::filesystem::path(directory) / file) << text;
}

// The files of a valid diff_drive_castor log by name; `overrides` replaces whole files (empty
// text removes the file).
inline std::map<std::string, std::string> ValidLogFiles(
    const std::map<std::string, std::string>& overrides = {}) {
  std::map<std::string, std::string> files = {
      {"vehicle.yaml", kLagrVehicleYaml},
      {"imu.csv",
       "# IMU, body frame\n"
       "t,ax,ay,az,gx,gy,gz\n"
       "0.00,0.10,0.00,9.81,0.0,0.0,0.01\n"
       "0.01,0.11,0.00,9.80,0.0,0.0,0.01\n"
       "0.02,0.12,0.01,9.81,0.0,0.0,0.02\n"
       "0.03,0.10,0.00,9.82,0.0,0.0,0.01\n"},
      // Columns in another order and an extra column the reader must ignore.
      {"wheels.csv",
       "right,t,left,motor_current\n"
       "4.0,0.00,4.1,1.5\n"
       "4.0,0.01,4.1,1.5\n"
       "4.1,0.02,4.0,1.6\n"},
      {"gps.csv",
       "t,x,y,z,vx,vy,vz,sd_xy\n"
       "0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.4\n"
       "1.0,1.0,0.0,0.0,1.0,0.0,0.0,\n"
       "2.0,2.0,0.0,0.0,1.0,0.0,0.0,nan\n"},
  };
  for (const auto& [file, text] : overrides) {
    if (text.empty()) {
      files.erase(file);
    } else {
      files[file] = text;
    }
  }
  return files;
}

// ValidLogFiles(overrides) written to a fresh directory `name`; returns its path.
inline std::string WriteValidLog(const std::string& name,
                                 const std::map<std::string, std::string>& overrides = {}) {
  const std::string dir = FreshDirectory(name);
  for (const auto& [file, text] : ValidLogFiles(overrides)) WriteText(dir, file, text);
  return dir;
}

// The bytes of a file.
inline std::string ReadFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

}  // namespace testing
}  // namespace slipgraph
