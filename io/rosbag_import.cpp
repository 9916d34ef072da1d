#include "io/rosbag_import.h"

#include <nav_msgs/Odometry.h>
#include <ros/exception.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/NavSatFix.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <optional>

#include "io/input_error.h"
#include "io/ros_log_builder.h"
#include "io/rosbag_records.h"

namespace slipgraph {

std::vector<SourceEntry> ListRosBag(const std::string& bag_path) {
  std::vector<SourceEntry> out;
  try {
    CheckRosBagRecords(bag_path);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    rosbag::View all(bag);
    std::vector<std::pair<std::string, std::string>> topics;
    for (const rosbag::ConnectionInfo* c : all.getConnections()) {
      const std::pair<std::string, std::string> entry{c->topic, c->datatype};
      if (std::find(topics.begin(), topics.end(), entry) == topics.end()) topics.push_back(entry);
    }
    std::sort(topics.begin(), topics.end());
    for (const auto& [topic, type] : topics) {
      rosbag::View view(bag, rosbag::TopicQuery(topic));
      SourceEntry e{topic, type, static_cast<long>(view.size()), 0.0};
      const double span = (view.getEndTime() - view.getBeginTime()).toSec();
      if (e.count > 1 && span > 0.0) e.rate_hz = (e.count - 1) / span;
      out.push_back(e);
    }
  } catch (const ros::Exception& e) {  // rosbag's and the deserializers' errors
    throw InputError(bag_path, 0, "", "", std::string("ROS bag: ") + e.what());
  }
  return out;
}

bool IsRosBag(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char header[13] = {};
  in.read(header, 12);
  return std::string(header) == "#ROSBAG V2.0";
}

namespace {

// The message `m` decoded as the data type `Message`. Bytes that do not decode as the type (fewer
// than it needs, or a definition other than the library's) are an InputError naming the bag, the
// topic and the time.
template <typename Message>
boost::shared_ptr<const Message> Decode(const rosbag::MessageInstance& m,
                                        const std::string& bag_path) {
  const auto fail = [&](const std::string& why) {
    throw InputError(bag_path, 0, m.getTopic(), RosTimeText(m.getTime().toSec()),
                     "message does not decode as " + m.getDataType() + ": " + why);
  };
  boost::shared_ptr<const Message> out;
  try {
    out = m.instantiate<Message>();
  } catch (const ros::Exception& e) {
    fail(e.what());
  }
  if (!out) fail("its definition (MD5 sum) is not the one this program reads");
  return out;
}

template <size_t N, typename Array>
std::array<double, N> Values(const Array& in) {
  std::array<double, N> out;
  std::copy(in.begin(), in.end(), out.begin());
  return out;
}

template <typename Vector3>
std::array<double, 3> Values3(const Vector3& v) {
  return {v.x, v.y, v.z};
}

// The message as ros_messages.h's, or nullopt for a type the importer does not read.
std::optional<RosMessage> ToRosMessage(const rosbag::MessageInstance& m,
                                       const std::string& bag_path) {
  const std::string& type = m.getDataType();
  if (type == kRosImuType) {
    const auto imu = Decode<sensor_msgs::Imu>(m, bag_path);
    RosImu out;
    out.stamp_s = imu->header.stamp.toSec();
    out.frame_id = imu->header.frame_id;
    out.orientation_xyzw = {imu->orientation.x, imu->orientation.y, imu->orientation.z,
                            imu->orientation.w};
    out.orientation_covariance = Values<9>(imu->orientation_covariance);
    out.angular_velocity = Values3(imu->angular_velocity);
    out.linear_acceleration = Values3(imu->linear_acceleration);
    return out;
  }
  if (type == kRosOdometryType) {
    const auto odom = Decode<nav_msgs::Odometry>(m, bag_path);
    RosOdometry out;
    out.stamp_s = odom->header.stamp.toSec();
    out.linear = Values3(odom->twist.twist.linear);
    out.angular = Values3(odom->twist.twist.angular);
    return out;
  }
  if (type == kRosNavSatFixType) {
    const auto fix = Decode<sensor_msgs::NavSatFix>(m, bag_path);
    RosNavSatFix out;
    out.stamp_s = fix->header.stamp.toSec();
    out.status = fix->status.status;
    out.latitude_deg = fix->latitude, out.longitude_deg = fix->longitude;
    out.altitude_m = fix->altitude;
    out.position_covariance = Values<9>(fix->position_covariance);
    out.position_covariance_type = fix->position_covariance_type;
    return out;
  }
  if (type == kRosJointStateType) {
    const auto js = Decode<sensor_msgs::JointState>(m, bag_path);
    RosJointState out;
    out.stamp_s = js->header.stamp.toSec();
    out.name = js->name, out.position = js->position, out.velocity = js->velocity;
    return out;
  }
  if (type == kRosTfMessageType) {
    const auto tf = Decode<tf2_msgs::TFMessage>(m, bag_path);
    RosTfMessage out;
    for (const geometry_msgs::TransformStamped& t : tf->transforms) {
      const auto& r = t.transform.rotation;
      out.transforms.push_back({t.header.frame_id,
                                t.child_frame_id,
                                Values3(t.transform.translation),
                                {r.x, r.y, r.z, r.w}});
    }
    return out;
  }
  return std::nullopt;
}

}  // namespace

void ForEachRosBagMessage(const std::string& bag_path, const std::vector<std::string>& topics,
                          const std::function<void(const std::string& topic, double time_s,
                                                   const RosMessage& message)>& visit) {
  try {
    CheckRosBagRecords(bag_path);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    rosbag::View view(bag, rosbag::TopicQuery(topics));
    for (const rosbag::MessageInstance& m : view) {
      const std::optional<RosMessage> message = ToRosMessage(m, bag_path);
      if (!message) {
        throw InputError(
            bag_path, 0, m.getTopic(), m.getDataType(),
            std::string("not a message type the importer reads (") + kRosTypesRead + ")");
      }
      visit(m.getTopic(), m.getTime().toSec(), *message);
    }
  } catch (const ros::Exception& e) {  // rosbag's and the deserializers' errors
    throw InputError(bag_path, 0, "", "", std::string("ROS bag: ") + e.what());
  }
}

DriveLog ImportRosBag(const std::string& bag_path, const std::string& mapping_path,
                      const Vehicle& vehicle, ImportReport* report) {
  RosLogBuilder builder(ReadRosMapping(mapping_path, RosBagKind::kRos1, vehicle), vehicle,
                        bag_path);
  ForEachRosBagMessage(bag_path, builder.topics(),
                       [&](const std::string& topic, double, const RosMessage& message) {
                         builder.Add(topic, message);
                       });
  return builder.Finish(report);
}

}  // namespace slipgraph
