// ROS messages (ros_messages.h) into a drive log, the same for a ROS 1 bag and a ROS 2 bag
// (sqlite3 or MCAP storage), driven by a mapping file (YAML) that names the topic of each stream
// and states the source's conventions:
//
//   format: ros_bag            # or ros1_bag / ros2_bag to insist on one kind of recording
//   imu:    {topic: /imu/data, body_from_sensor: [[0, 0, -1], [-1, 0, 0], [0, 1, 0]],
//            attitude: true, yaw_offset: 1.97}
//   wheels: {topic: /husky_velocity_controller/odom, from: body_twist, track: 0.555,
//            radius: 0.1651}
//   gps:    {topic: /fix, sd_v: 0.2}
//
// imu: sensor_msgs/Imu. Its mounting is either `body_from_sensor`, the rotation (rows: the body's
// x, y, z axes in sensor coordinates), or `body_frame: base_link`, which takes it from the
// recording's static transforms (the top-level `tf_topic`, /tf_static by default:
// tf2_msgs/TFMessage) along the tree from that frame to the IMU messages' frame_id. The rotation
// is applied to acceleration and rate, and to the orientation when `attitude: true` writes
// attitude.csv from it (roll, pitch, yaw REP-103; sd from the orientation covariance); yaw_offset
// (rad) is added to the yaw, for a sensor whose heading is not referenced to east.
// wheels, `from: body_twist`: nav_msgs/Odometry's body twist turned into side speeds,
// left = (v - w c/2) / r, right = (v + w c/2) / r (the controller's own odometry: it carries no
// slip of its own). ROS's diff_drive_controller computes that twist with its wheel_separation
// times wheel_separation_multiplier (and wheel_radius times wheel_radius_multiplier): `track` c
// and `radius` r set to those products give back the wheels' own speeds; the geometric track
// gives side speeds whose difference reads the odometry's yaw rate, a smaller one on a skid-steer
// whose multiplier is above 1 (a Husky's 1.875). `from: joint_state`: sensor_msgs/JointState's
// velocities (rad/s), each of the vehicle's wheels (left, right; or fl, ml, rl, fr, mr, rr) the
// mean of the joints `joints` lists for it, times its sign in `signs` (1 when not listed):
//   wheels: {topic: /joint_states, from: joint_state,
//            joints: {left: [front_left_wheel, rear_left_wheel], right: [front_right_wheel,
//                     rear_right_wheel]}, signs: {left: 1, right: 1}}
// gps: sensor_msgs/NavSatFix; positions in a local ENU frame at the first fix (WGS84,
// GeographicLib's LocalCartesian), velocity by central difference of the positions (a fix has
// none), sd_xy from the position covariance. Header stamps are the times, shifted so the earliest
// is 0. Every choice is reported, one line each.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/import_report.h"
#include "io/ros_messages.h"

namespace slipgraph {

// Which kind of recording a mapping accepts.
enum class RosBagKind { kRos1, kRos2 };

// A ROS mapping file, read and checked.
struct RosMapping {
  std::string path;                                         // the file, for errors
  std::string format;                                       // ros_bag, ros1_bag or ros2_bag
  std::string imu_topic, wheel_topic, gps_topic, tf_topic;  // "" when the stream is not mapped
  bool imu_from_tf = false;  // body_frame given: the mounting from the static transforms
  std::string body_frame;
  std::array<double, 9> body_from_sensor{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
  bool attitude = false;
  double yaw_offset_rad = 0.0;
  std::string wheels_from;               // body_twist or joint_state
  double track_m = 0.0, radius_m = 0.0;  // body_twist
  // joint_state: per wheel of the vehicle (WheelNames order), its joints and its sign.
  std::vector<std::vector<std::string>> wheel_joints;
  std::vector<double> wheel_signs;
  double gps_sd_v = kMissing;  // as the mapping states it; kMissing when it does not

  // The topics to read, the static transforms' among them when the mounting comes from them.
  std::vector<std::string> topics() const;
};

// Throws InputError naming the file and key: an unknown key, a missing one, a rotation that is
// not one, a format other than those above or one that excludes `kind`, joints for a wheel the
// vehicle does not have.
RosMapping ReadRosMapping(const std::string& mapping_path, RosBagKind kind, const Vehicle& vehicle);

// Collects the messages of the mapped topics, in any order, and builds the log.
class RosLogBuilder {
 public:
  RosLogBuilder(RosMapping mapping, const Vehicle& vehicle, std::string source_path);

  // A message of `topic`. Throws InputError naming the recording, the topic and the stamp when
  // the message is not of the type the mapping's stream needs.
  void Add(const std::string& topic, const RosMessage& message);

  // The drive log, its samples readable (KeepReadableSamples) and its times from 0. Throws
  // InputError when a mapped topic had no message, or the IMU's mounting cannot be found in the
  // static transforms.
  DriveLog Finish(ImportReport* report);

  // The topics the mapping reads.
  std::vector<std::string> topics() const { return mapping_.topics(); }

 private:
  RosMapping mapping_;
  Vehicle vehicle_;
  std::string source_path_;
  std::vector<RosImu> imu_;
  std::vector<RosOdometry> odometry_;
  std::vector<RosJointState> joints_;
  std::vector<RosNavSatFix> fixes_;
  std::vector<RosTransform> static_transforms_;
};

}  // namespace slipgraph
