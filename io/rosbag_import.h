// Import of ROS 1 bags into the drive-log format, read with Debian's ROS bag libraries
// (librosbag-dev), driven by a mapping file (YAML) that names the topic of each stream and states
// the source's conventions:
//
//   format: ros1_bag
//   imu:    {topic: /imu/data, body_from_sensor: [[0, 0, -1], [-1, 0, 0], [0, 1, 0]],
//            attitude: true, yaw_offset: 1.97}
//   wheels: {topic: /husky_velocity_controller/odom, from: body_twist, track: 0.555,
//            radius: 0.1651}
//   gps:    {topic: /fix, sd_v: 0.2}
//
// imu: sensor_msgs/Imu; body_from_sensor is the rotation (rows: the body's x, y, z axes in sensor
// coordinates) applied to acceleration and rate, and to the orientation when `attitude: true`
// writes attitude.csv from it (roll, pitch, yaw REP-103; sd from the orientation covariance);
// yaw_offset (rad) is added to the yaw, for a sensor whose heading is not referenced to east.
// wheels: nav_msgs/Odometry's body twist turned into side speeds, left = (v - w c/2) / r,
// right = (v + w c/2) / r (the controller's own odometry: it carries no slip of its own).
// gps: sensor_msgs/NavSatFix; positions in a local ENU frame at the first fix (equirectangular,
// exact to millimetres over a few km), velocity by central difference of the positions (a fix has
// none), sd_xy from the position covariance. Header stamps are the times, shifted so the earliest
// is 0. Every choice is reported, one line each.
#pragma once

#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/import_report.h"
#include "io/matlab_import.h"  // SourceEntry

namespace slipgraph {

// Throws InputError naming the mapping file and key, or the bag and topic.
DriveLog ImportRosBag(const std::string& bag_path, const std::string& mapping_path,
                      const Vehicle& vehicle, ImportReport* report);

// Every topic of a bag with its message type, count and rate. Throws InputError when the bag
// cannot be read.
std::vector<SourceEntry> ListRosBag(const std::string& bag_path);

// True when the file starts with the ROS 1 bag header ("#ROSBAG V2.0").
bool IsRosBag(const std::string& path);

}  // namespace slipgraph
