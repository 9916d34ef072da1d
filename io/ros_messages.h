// The ROS messages the importers read, as plain values: decoded from a ROS 1 bag by the rosbag
// libraries (rosbag_import) or from a ROS 2 bag's CDR bytes (ros2_messages), then turned into a
// drive log by one builder (ros_log_builder) whatever the recording. Only the fields the import
// uses; stamps are the header's, in seconds.
#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

namespace slipgraph {

// sensor_msgs/Imu.
struct RosImu {
  double stamp_s = 0.0;
  std::string frame_id;
  std::array<double, 4> orientation_xyzw{};
  std::array<double, 9> orientation_covariance{};
  std::array<double, 3> angular_velocity{}, linear_acceleration{};
};

// nav_msgs/Odometry: its body twist.
struct RosOdometry {
  double stamp_s = 0.0;
  std::array<double, 3> linear{}, angular{};
};

// sensor_msgs/NavSatFix.
struct RosNavSatFix {
  double stamp_s = 0.0;
  int status = -1;  // NavSatStatus: -1 no fix, 0 fix, 1 SBAS, 2 GBAS
  double latitude_deg = 0.0, longitude_deg = 0.0, altitude_m = 0.0;
  std::array<double, 9> position_covariance{};
  int position_covariance_type = 0;  // 0 unknown, 1 approximated, 2 diagonal known, 3 known
};

// sensor_msgs/JointState (its effort is not kept).
struct RosJointState {
  double stamp_s = 0.0;
  std::vector<std::string> name;
  std::vector<double> position, velocity;
};

// One geometry_msgs/TransformStamped: p_parent = R(rotation) p_child + translation.
struct RosTransform {
  std::string parent_frame, child_frame;
  std::array<double, 3> translation{};
  std::array<double, 4> rotation_xyzw{};
};

// tf2_msgs/TFMessage.
struct RosTfMessage {
  std::vector<RosTransform> transforms;
};

using RosMessage = std::variant<RosImu, RosOdometry, RosNavSatFix, RosJointState, RosTfMessage>;

// A stamp or a receive time (s) as an importer's error names it: "t=12.345678901".
inline std::string RosTimeText(double t_s) {
  char text[40];
  std::snprintf(text, sizeof(text), "t=%.9f", t_s);
  return text;
}

// The ROS 1 names of the types above ("sensor_msgs/Imu"); ROS 2 inserts "/msg/".
inline constexpr const char* kRosImuType = "sensor_msgs/Imu";
inline constexpr const char* kRosOdometryType = "nav_msgs/Odometry";
inline constexpr const char* kRosNavSatFixType = "sensor_msgs/NavSatFix";
inline constexpr const char* kRosJointStateType = "sensor_msgs/JointState";
inline constexpr const char* kRosTfMessageType = "tf2_msgs/TFMessage";
// The same, for an error that says what is read.
inline constexpr const char* kRosTypesRead =
    "sensor_msgs/Imu, nav_msgs/Odometry, sensor_msgs/NavSatFix, sensor_msgs/JointState, "
    "tf2_msgs/TFMessage";

}  // namespace slipgraph
