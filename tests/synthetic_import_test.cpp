// The importers on tiny recordings written here, so that they are tested without the real logs in
// ../shared: a MATLAB v7.3 file (HDF5, written with the HDF5 library) and a ROS 1 bag (written
// with rosbag), each with a known motion. Checked: every stream's count, values, frame and sign
// conventions, the GNSS velocity by central difference, the shifted clock, and the errors that
// name the file and the variable, topic or key.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "io/hdf5_matrix.h"
#include "io/input_error.h"
#include "io/matlab_import.h"
#include "io/rosbag_import.h"
#include "io/yaml_config.h"

namespace slipgraph {
namespace {

std::string TempPath(const std::string& name) { return ::testing::TempDir() + "/" + name; }

std::string WriteText(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

Vehicle TinyVehicle() {
  Vehicle v;
  v.name = "tiny";
  v.mass_kg = 50.0;
  v.wheel_radius_m = 0.1;
  v.track_width_m = 0.5;
  return v;
}

// Writes `values` as a dataset of HDF5 dimensions `dims` (row-major): MATLAB's R x C matrix is
// HDF5's C x R, so a MATLAB 1 x N row is {N, 1} and an N x 3 table is {3, N}.
void WriteDataset(hid_t file, const std::string& name, const std::vector<hsize_t>& dims,
                  const std::vector<double>& values) {
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t set =
      H5Dcreate2(file, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(set, 0) << name;
  ASSERT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Dclose(set);
  H5Sclose(space);
}

// 2 s of a rover on a z-down IMU at 100 Hz from t = 50 s, wheels at 10 Hz (left reads negative
// forward, two wheels a side), ENU fixes at 5 Hz moving east at 0.5 m/s, as MATLAB stores them.
std::string WriteTinyMat(const std::string& name, int gps_fixes = 10) {
  const std::string path = TempPath(name);
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(file, 0);
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

const char kMatMapping[] =
    "format: matlab_v73\n"
    "imu: {t: tTimu, ax: Ax, ay: Ay, az: Az, gx: Gx, gy: Gy, gz: Gz, frame: z_down}\n"
    "wheels:\n"
    "  t: tTodom\n"
    "  left: [frontLeftVel, rearLeftVel]\n"
    "  right: [frontRightVel, rearRightVel]\n"
    "  left_sign: -1\n"
    "  right_sign: 1\n"
    "gps: {t: tTGPS, enu: ENUGPS, sd_xy: 2.5, sd_v: 0.2}\n";

TEST(SyntheticImport, MatlabFileEveryStreamAndConvention) {
  const std::string mat = WriteTinyMat("tiny.mat");
  const std::string mapping = WriteText("tiny_mat.yaml", kMatMapping);
  ImportReport report;
  const DriveLog log = ImportMatlab(mat, mapping, TinyVehicle(), &report);
  ASSERT_EQ(log.imu.size(), 200u);
  ASSERT_EQ(log.wheels.size(), 20u);
  ASSERT_EQ(log.gps.size(), 10u);
  // The clock starts at the earliest stamp (the IMU's, 50 s).
  EXPECT_NEAR(log.imu.front().t, 0.0, 1e-12);
  EXPECT_NEAR(log.wheels.front().t, 0.05, 1e-9);
  EXPECT_NEAR(log.gps.front().t, 0.1, 1e-9);
  // z_down: rotated 180 deg about x, y and z negated (gravity +9.8 on z at rest).
  EXPECT_EQ(log.imu[7].ax, 0.2);
  EXPECT_EQ(log.imu[7].ay, -0.1);
  EXPECT_EQ(log.imu[7].az, 9.8);
  EXPECT_EQ(log.imu[7].gx, 0.01);
  EXPECT_EQ(log.imu[7].gy, -0.02);
  EXPECT_EQ(log.imu[7].gz, 0.3);
  // Each side the mean of its wheels times its sign.
  EXPECT_DOUBLE_EQ(log.wheels[3].omega_radps[0], 5.0);
  EXPECT_DOUBLE_EQ(log.wheels[3].omega_radps[1], 5.0);
  // ENU positions as stored; velocity by central difference (0.1 m per 0.2 s east).
  EXPECT_DOUBLE_EQ(log.gps[4].x, 0.4);
  EXPECT_DOUBLE_EQ(log.gps[4].y, 2.0);
  EXPECT_NEAR(log.gps[4].vx, 0.5, 1e-9);
  EXPECT_NEAR(log.gps[4].vy, 0.0, 1e-12);
  EXPECT_NEAR(log.gps.back().vx, 0.5, 1e-9);  // one-sided at the ends
  EXPECT_EQ(log.gps[4].sd_xy, 2.5);
  EXPECT_EQ(log.gps[4].sd_v, 0.2);
  ASSERT_EQ(report.lines.size(), 4u);
  EXPECT_NE(report.lines[0].find("frame z_down"), std::string::npos) << report.lines[0];

  // import --list: the variables and their HDF5 dimensions.
  bool listed = false;
  for (const SourceEntry& e : ListMatlab(mat)) {
    if (e.name == "ENUGPS") {
      EXPECT_EQ(e.type, "3 x 10");
      EXPECT_EQ(e.count, 30);
      listed = true;
    }
  }
  EXPECT_TRUE(listed);
}

// The message of the InputError `f` throws (empty and a failure when it throws none).
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(SyntheticImport, MatlabErrorsNameTheFileAndTheVariable) {
  const std::string mat = WriteTinyMat("tiny_short_gps.mat", 10);
  ImportReport report;
  const std::string missing =
      WriteText("missing_var.yaml",
                std::string(kMatMapping).replace(std::string(kMatMapping).find("Az"), 2, "Azz"));
  std::string e = ErrorOf([&] { ImportMatlab(mat, missing, TinyVehicle(), &report); });
  EXPECT_NE(e.find("tiny_short_gps.mat"), std::string::npos) << e;
  EXPECT_NE(e.find("no variable named 'Azz'"), std::string::npos) << e;

  const std::string wrong_t = WriteText(
      "wrong_t.yaml",
      std::string(kMatMapping).replace(std::string(kMatMapping).find("t: tTodom"), 9, "t: tTimu"));
  e = ErrorOf([&] { ImportMatlab(mat, wrong_t, TinyVehicle(), &report); });
  EXPECT_NE(e.find("frontLeftVel"), std::string::npos) << e;
  EXPECT_NE(e.find("has 20 values for 200 wheel stamps"), std::string::npos) << e;

  const std::string not_hdf5 = WriteText("not_hdf5.mat", "MATLAB 5.0 MAT-file\n");
  e = ErrorOf([&] { ReadHdf5Matrix(not_hdf5, "Ax"); });
  EXPECT_NE(e.find("cannot open as HDF5"), std::string::npos) << e;
  e = ErrorOf([&] { ReadHdf5Matrix(mat, "ENUGPS").Vector("ENUGPS"); });
  EXPECT_NE(e.find("expected a vector, found a 3 x 10 matrix"), std::string::npos) << e;
}

const char kBagMapping[] =
    "format: ros1_bag\n"
    "imu:\n"
    "  topic: /imu\n"
    "  body_from_sensor: [[0, 0, -1], [-1, 0, 0], [0, 1, 0]]\n"
    "  attitude: true\n"
    "  yaw_offset: 0.5\n"
    "wheels: {topic: /odom, from: body_twist, track: 0.5, radius: 0.1}\n"
    "gps: {topic: /fix, sd_v: 0.3}\n";

constexpr double kEarthRadiusM = 6378137.0;

// 2 s from t = 1000 s: an IMU at 50 Hz mounted as kBagMapping's body_from_sensor says, yawed 0.2
// rad; odometry at 10 Hz (1 m/s, 0.2 rad/s); fixes at 2 Hz moving north at 1 m/s, the first
// without a fix (skipped).
std::string WriteTinyBag(const std::string& name) {
  const std::string path = TempPath(name);
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
    fix.latitude = 45.0 + (0.5 * i) / kEarthRadiusM * 180.0 / M_PI;
    fix.longitude = 7.0;
    fix.altitude = 300.0;
    fix.position_covariance[0] = 4.0;
    fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
    bag.write("/fix", fix.header.stamp, fix);
  }
  bag.close();
  return path;
}

TEST(SyntheticImport, RosBagEveryStreamAndConvention) {
  const std::string bag = WriteTinyBag("tiny.bag");
  const std::string mapping = WriteText("tiny_bag.yaml", kBagMapping);
  ImportReport report;
  const DriveLog log = ImportRosBag(bag, mapping, TinyVehicle(), &report);
  ASSERT_EQ(log.imu.size(), 100u);
  ASSERT_EQ(log.attitude.size(), 100u);
  ASSERT_EQ(log.wheels.size(), 20u);
  ASSERT_EQ(log.gps.size(), 4u);  // the fix without a fix is skipped
  EXPECT_NEAR(log.imu.front().t, 0.0, 1e-9);
  EXPECT_NEAR(log.wheels.front().t, 0.01, 1e-6);
  EXPECT_NEAR(log.gps.front().t, 0.55, 1e-6);
  // The IMU rotated into the body frame.
  EXPECT_NEAR(log.imu[5].ax, 0.3, 1e-12);
  EXPECT_NEAR(log.imu[5].ay, 0.1, 1e-12);
  EXPECT_NEAR(log.imu[5].az, 9.8, 1e-12);
  EXPECT_NEAR(log.imu[5].gz, 0.2, 1e-12);
  // Attitude: the body's yaw plus the mapping's offset; level; the stated sd.
  EXPECT_NEAR(log.attitude[5].yaw, 0.7, 1e-9);
  EXPECT_NEAR(log.attitude[5].pitch, 0.0, 1e-9);
  EXPECT_NEAR(log.attitude[5].roll, 0.0, 1e-9);
  // Side speeds from the body twist: (v -+ track / 2 w) / r.
  EXPECT_NEAR(log.wheels[4].omega_radps[0], 9.5, 1e-12);
  EXPECT_NEAR(log.wheels[4].omega_radps[1], 10.5, 1e-12);
  // Local ENU at the first fix: north at 1 m/s, the stated position sd.
  EXPECT_NEAR(log.gps[0].y, 0.0, 1e-9);
  EXPECT_NEAR(log.gps[2].y, 1.0, 1e-6);
  EXPECT_NEAR(log.gps[2].vy, 1.0, 1e-6);
  EXPECT_NEAR(log.gps[2].vx, 0.0, 1e-9);
  EXPECT_EQ(log.gps[2].sd_xy, 2.0);
  EXPECT_EQ(log.gps[2].sd_v, 0.3);
  bool skipped_said = false;
  for (const std::string& line : report.lines) {
    skipped_said = skipped_said || line.find("skipped: 1 messages") != std::string::npos;
  }
  EXPECT_TRUE(skipped_said);
  // import --list: the topics, their types and rates.
  const std::vector<SourceEntry> topics = ListRosBag(bag);
  ASSERT_EQ(topics.size(), 3u);
  EXPECT_EQ(topics[1].name, "/imu");
  EXPECT_EQ(topics[1].type, "sensor_msgs/Imu");
  EXPECT_EQ(topics[1].count, 100);
  EXPECT_NEAR(topics[1].rate_hz, 50.0, 1e-6);
}

TEST(SyntheticImport, RosBagErrorsNameTheTopicAndTheKey) {
  const std::string bag = WriteTinyBag("tiny_errors.bag");
  ImportReport report;
  std::string mapping_text = kBagMapping;
  mapping_text.replace(mapping_text.find("topic: /fix"), 11, "topic: /gnss");
  const std::string no_topic = WriteText("no_topic.yaml", mapping_text);
  std::string e = ErrorOf([&] { ImportRosBag(bag, no_topic, TinyVehicle(), &report); });
  EXPECT_NE(e.find("gps.topic"), std::string::npos) << e;
  EXPECT_NE(e.find("no messages on this topic"), std::string::npos) << e;

  mapping_text = kBagMapping;
  mapping_text.replace(mapping_text.find("topic: /imu"), 11, "topic: /odom");
  const std::string wrong_type = WriteText("wrong_type.yaml", mapping_text);
  e = ErrorOf([&] { ImportRosBag(bag, wrong_type, TinyVehicle(), &report); });
  EXPECT_NE(e.find("not a sensor_msgs/Imu"), std::string::npos) << e;

  const std::string not_a_bag = WriteText("not_a.bag", "#ROSBAG V1.2\nnothing\n");
  e = ErrorOf(
      [&] { ImportRosBag(not_a_bag, WriteText("ok.yaml", kBagMapping), TinyVehicle(), &report); });
  EXPECT_NE(e.find("ROS bag: "), std::string::npos) << e;
}

}  // namespace
}  // namespace slipgraph
