// Writes a tiny ROS 2 bag as a robot with ROS 2 records one, for the command-line tests of
// `import`: 2 s of an IMU at 50 Hz in its own frame (imu_link, mounted as tests/tiny_recordings.h's
// bag says, given by /tf_static through a mount frame), wheel joints at 10 Hz on /joint_states
// (two a side, the left ones counting backwards), fixes at 2 Hz moving north at 1 m/s. Written as
// a bag directory (metadata.yaml and an MCAP file, zstd chunks) and as a sqlite3 .db3, with the
// mapping that reads them. Usage: tiny_ros2_bag DIRECTORY
#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/ros2_bag_writer.h"
#include "tests/tiny_recordings.h"

namespace {

using slipgraph::testing::Store;
using slipgraph::testing::StoredMessage;

std::array<double, 4> Xyzw(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  return {q.x(), q.y(), q.z(), q.w()};
}

std::vector<StoredMessage> Messages() {
  std::vector<StoredMessage> out;
  Eigen::Matrix3d body_from_sensor;
  body_from_sensor << 0, 0, -1, -1, 0, 0, 0, 1, 0;
  const Eigen::Matrix3d body_from_mount =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  slipgraph::RosTfMessage tf;
  tf.transforms.push_back({"base_link", "mount", {0.2, 0, 0.3}, Xyzw(body_from_mount)});
  tf.transforms.push_back(
      {"mount", "imu_link", {0, 0, 0}, Xyzw(body_from_mount.transpose() * body_from_sensor)});
  out.push_back(Store("/tf_static", 1000.0, tf));
  for (int i = 0; i < 100; ++i) {
    slipgraph::RosImu imu;
    imu.stamp_s = 1000.0 + 0.02 * i, imu.frame_id = "imu_link";
    imu.linear_acceleration = {-0.1, 9.8, -0.3};  // body (0.3, 0.1, 9.8)
    imu.angular_velocity = {0.0, 0.2, 0.0};       // body yaw rate 0.2
    out.push_back(Store("/imu/data", imu.stamp_s, imu));
    if (i % 5 == 0) {
      slipgraph::RosJointState js;
      js.stamp_s = 1000.01 + 0.02 * i;
      js.name = {"front_left_wheel", "rear_left_wheel", "front_right_wheel", "rear_right_wheel"};
      js.position = {0, 0, 0, 0};
      js.velocity = {-9.4, -9.6, 10.5, 10.5};
      out.push_back(Store("/joint_states", js.stamp_s, js));
    }
    if (i % 25 == 0) {
      slipgraph::RosNavSatFix fix;
      fix.stamp_s = 1000.05 + 0.02 * i;
      fix.status = 0;
      const double north_m = 0.02 * i;
      fix.latitude_deg =
          45.0 + north_m / (slipgraph::testing::MeridianRadiusM(45.0) + 300.0) * 180.0 / M_PI;
      fix.longitude_deg = 7.0, fix.altitude_m = 300.0;
      fix.position_covariance[0] = 4.0, fix.position_covariance_type = 2;
      out.push_back(Store("/fix", fix.stamp_s, fix));
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: tiny_ros2_bag DIRECTORY\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::filesystem::create_directories(dir + "/tiny_ros2");
  const std::vector<StoredMessage> messages = Messages();
  slipgraph::testing::WriteMcap(dir + "/tiny_ros2/tiny_ros2_0.mcap", messages, "zstd");
  std::ofstream(dir + "/tiny_ros2/metadata.yaml")
      << "rosbag2_bagfile_information:\n  version: 8\n  storage_identifier: mcap\n"
         "  relative_file_paths: [tiny_ros2_0.mcap]\n";
  slipgraph::testing::WriteSqliteBag(dir + "/tiny_ros2.db3", messages);
  std::ofstream(dir + "/tiny_ros2.yaml")
      << "format: ros2_bag\n"
         "imu: {topic: /imu/data, body_frame: base_link}\n"
         "wheels:\n"
         "  topic: /joint_states\n"
         "  from: joint_state\n"
         "  joints: {left: [front_left_wheel, rear_left_wheel],\n"
         "           right: [front_right_wheel, rear_right_wheel]}\n"
         "  signs: {left: -1}\n"
         "gps: {topic: /fix, sd_v: 0.3}\n";
  return 0;
}
