// Tiny recordings with a known motion, written with the libraries the importers read them with
// (HDF5 for MATLAB v7.3, rosbag for ROS 1), and mappings for them: the importers' tests and
// fuzzers use them instead of the real logs in ../shared.
#pragma once

#include <hdf5.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model/vehicle.h"

namespace slipgraph {
namespace testing {

// `name` in `directory`.
inline std::string PathIn(const std::string& directory, const std::string& name) {
  return directory + "/" + name;
}

inline std::string WriteText(const std::string& directory, const std::string& name,
                             const std::string& text) {
  const std::string path = PathIn(directory, name);
  std::ofstream(path) << text;
  return path;
}

// A whole vehicle (every dimension vehicle.yaml requires of a diff_drive_castor).
inline Vehicle TinyVehicle() {
  Vehicle v;
  v.name = "tiny";
  v.mass_kg = 50.0;
  v.yaw_inertia_kgm2 = 2.0;
  v.wheel_radius_m = 0.1;
  v.track_width_m = 0.5;
  v.cg_to_front_m = 0.2;
  v.cg_to_rear_m = 0.2;
  v.cg_height_m = 0.15;
  return v;
}

// Writes `values` as a dataset of HDF5 dimensions `dims` (row-major): MATLAB's R x C matrix is
// HDF5's C x R, so a MATLAB 1 x N row is {N, 1} and an N x 3 table is {3, N}.
inline void WriteDataset(hid_t file, const std::string& name, const std::vector<hsize_t>& dims,
                         const std::vector<double>& values) {
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t set =
      H5Dcreate2(file, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0 ||
      H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    throw std::runtime_error("cannot write dataset " + name);
  }
  H5Dclose(set);
  H5Sclose(space);
}

// 2 s of a rover on a z-down IMU at 100 Hz from t = 50 s, wheels at 10 Hz (left reads negative
// forward, two wheels a side), ENU fixes at 5 Hz moving east at 0.5 m/s, as MATLAB stores them.
inline std::string WriteTinyMat(const std::string& directory, const std::string& name,
                                int gps_fixes = 10) {
  const std::string path = PathIn(directory, name);
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("cannot create " + path);
  std::vector<double> t_imu, ax, ay, az, gx, gy, gz;
  for (int i = 0; i < 200; ++i) {
    t_imu.push_back(50.0 + 0.01 * i);
    ax.push_back(0.2), ay.push_back(0.1), az.push_back(-9.8);
    gx.push_back(0.01), gy.push_back(0.02), gz.push_back(-0.3);
  }
  for (const auto& [n, v] : {std::pair<const char*, std::vector<double>*>{"tTimu", &t_imu},
                             {"Ax", &ax},
                             {"Ay", &ay},
                             {"Az", &az},
                             {"Gx", &gx},
                             {"Gy", &gy},
                             {"Gz", &gz}}) {
    WriteDataset(file, n, {v->size(), 1}, *v);
  }
  std::vector<double> t_odom, fl, rl, fr, rr;
  for (int i = 0; i < 20; ++i) {
    t_odom.push_back(50.05 + 0.1 * i);
    fl.push_back(-4.0), rl.push_back(-6.0), fr.push_back(5.5), rr.push_back(4.5);
  }
  WriteDataset(file, "tTodom", {1, t_odom.size()}, t_odom);  // a MATLAB N x 1 column
  WriteDataset(file, "frontLeftVel", {fl.size(), 1}, fl);
  WriteDataset(file, "rearLeftVel", {rl.size(), 1}, rl);
  WriteDataset(file, "frontRightVel", {fr.size(), 1}, fr);
  WriteDataset(file, "rearRightVel", {rr.size(), 1}, rr);
  std::vector<double> t_gps, enu;
  for (int i = 0; i < gps_fixes; ++i) t_gps.push_back(50.1 + 0.2 * i);
  for (int axis = 0; axis < 3; ++axis) {  // HDF5 {3, N}: the east row, then north, then up
    for (int i = 0; i < gps_fixes; ++i) enu.push_back(axis == 0 ? 0.1 * i : axis == 1 ? 2.0 : 0.5);
  }
  WriteDataset(file, "tTGPS", {t_gps.size(), 1}, t_gps);
  WriteDataset(file, "ENUGPS", {3, static_cast<hsize_t>(gps_fixes)}, enu);
  H5Fclose(file);
  return path;
}

inline const char kMatMapping[] =
    "format: matlab_v73\n"
    "imu: {t: tTimu, ax: Ax, ay: Ay, az: Az, gx: Gx, gy: Gy, gz: Gz, frame: z_down}\n"
    "wheels:\n"
    "  t: tTodom\n"
    "  left: [frontLeftVel, rearLeftVel]\n"
    "  right: [frontRightVel, rearRightVel]\n"
    "  left_sign: -1\n"
    "  right_sign: 1\n"
    "gps: {t: tTGPS, enu: ENUGPS, sd_xy: 2.5, sd_v: 0.2}\n";

inline const char kBagMapping[] =
    "format: ros1_bag\n"
    "imu:\n"
    "  topic: /imu\n"
    "  body_from_sensor: [[0, 0, -1], [-1, 0, 0], [0, 1, 0]]\n"
    "  attitude: true\n"
    "  yaw_offset: 0.5\n"
    "wheels: {topic: /odom, from: body_twist, track: 0.5, radius: 0.1}\n"
    "gps: {topic: /fix, sd_v: 0.3}\n";

// WGS84's meridian radius of curvature at a latitude: metres north per radian of latitude there
// on the ellipsoid (a(1 - e^2) / (1 - e^2 sin^2 phi)^1.5; 6367.4 km at 45 deg, where a sphere of
// the equatorial radius is 0.17 % long); at a height h above it, M + h.
inline double MeridianRadiusM(double latitude_deg) {
  constexpr double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double s = std::sin(latitude_deg * M_PI / 180.0);
  return a * (1.0 - e2) / std::pow(1.0 - e2 * s * s, 1.5);
}

// 2 s from t = 1000 s: an IMU at 50 Hz mounted as kBagMapping's body_from_sensor says, yawed 0.2
// rad; odometry at 10 Hz (1 m/s, 0.2 rad/s); fixes at 2 Hz moving north at 1 m/s, the first
// without a fix (skipped).
inline std::string WriteTinyBag(const std::string& directory, const std::string& name) {
  const std::string path = PathIn(directory, name);
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  for (int i = 0; i < 100; ++i) {
    sensor_msgs::Imu imu;
    imu.header.stamp = ros::Time(1000.0 + 0.02 * i);
    // Body (0.3, 0.1, 9.8) in the sensor frame: sensor = body_from_sensor^T * body.
    imu.linear_acceleration.x = -0.1, imu.linear_acceleration.y = 9.8;
    imu.linear_acceleration.z = -0.3;
    imu.angular_velocity.x = 0.0, imu.angular_velocity.y = 0.2, imu.angular_velocity.z = 0.0;
    // World from sensor = world from body (yaw 0.2) x body from sensor.
    const Eigen::Matrix3d world_from_body =
        Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    Eigen::Matrix3d body_from_sensor;
    body_from_sensor << 0, 0, -1, -1, 0, 0, 0, 1, 0;
    const Eigen::Quaterniond q(world_from_body * body_from_sensor);
    imu.orientation.w = q.w(), imu.orientation.x = q.x(), imu.orientation.y = q.y();
    imu.orientation.z = q.z();
    imu.orientation_covariance[0] = 0.0001;
    bag.write("/imu", imu.header.stamp, imu);
  }
  for (int i = 0; i < 20; ++i) {
    nav_msgs::Odometry odom;
    odom.header.stamp = ros::Time(1000.01 + 0.1 * i);
    odom.twist.twist.linear.x = 1.0;
    odom.twist.twist.angular.z = 0.2;
    bag.write("/odom", odom.header.stamp, odom);
  }
  for (int i = 0; i < 5; ++i) {
    sensor_msgs::NavSatFix fix;
    fix.header.stamp = ros::Time(1000.05 + 0.5 * i);
    fix.status.status =
        i == 0 ? sensor_msgs::NavSatStatus::STATUS_NO_FIX : sensor_msgs::NavSatStatus::STATUS_FIX;
    fix.latitude = 45.0 + (0.5 * i) / (MeridianRadiusM(45.0) + 300.0) * 180.0 / M_PI;
    fix.longitude = 7.0;
    fix.altitude = 300.0;
    fix.position_covariance[0] = 4.0;
    fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
    bag.write("/fix", fix.header.stamp, fix);
  }
  bag.close();
  return path;
}

}  // namespace testing
}  // namespace slipgraph
