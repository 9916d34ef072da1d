#include "io/rosbag_import.h"

#include <nav_msgs/Odometry.h>
#include <ros/exception.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <tuple>

#include "io/input_error.h"
#include "io/mapping_file.h"
#include "io/rosbag_records.h"
#include "io/yaml_errors.h"

namespace slipgraph {
namespace {

std::string Text(const YAML::Node& node, const std::string& key, const std::string& path,
                 const std::string& section) {
  if (!node[key]) throw InputError(path, 0, section + "." + key, "", "missing key");
  return node[key].as<std::string>();
}

double Number(const YAML::Node& node, const std::string& key, const std::string& path,
              const std::string& section) {
  if (!node[key]) throw InputError(path, 0, section + "." + key, "", "missing key");
  return node[key].as<double>();
}

Eigen::Matrix3d Rotation(const YAML::Node& node, const std::string& path) {
  if (!node) return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d m;
  if (!node.IsSequence() || node.size() != 3) {
    throw InputError(path, node.Mark().line + 1, "imu.body_from_sensor", "",
                     "expected 3 rows of 3 numbers");
  }
  for (int r = 0; r < 3; ++r) {
    if (!node[r].IsSequence() || node[r].size() != 3) {
      throw InputError(path, node.Mark().line + 1, "imu.body_from_sensor", "",
                       "expected 3 rows of 3 numbers");
    }
    for (int c = 0; c < 3; ++c) m(r, c) = node[r][c].as<double>();
  }
  if (!(m * m.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || m.determinant() < 0.0) {
    throw InputError(path, node.Mark().line + 1, "imu.body_from_sensor", "",
                     "not a rotation (orthonormal, determinant +1)");
  }
  return m;
}

}  // namespace

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

// The message `m` as a `Message`, null when it is of another type. Bytes that do not decode as
// the type (fewer than it needs) are an InputError naming the bag, the topic and the time.
template <typename Message>
boost::shared_ptr<const Message> Decode(const rosbag::MessageInstance& m,
                                        const std::string& bag_path) {
  try {
    return m.instantiate<Message>();
  } catch (const ros::Exception& e) {
    char time[32];
    std::snprintf(time, sizeof(time), "t=%.6f", m.getTime().toSec());
    throw InputError(bag_path, 0, m.getTopic(), time,
                     "message does not decode as " + m.getDataType() + ": " + e.what());
  }
}

DriveLog Import(const std::string& bag_path, const std::string& mapping_path,
                const Vehicle& vehicle, ImportReport* report) {
  const YAML::Node mapping = LoadYamlFile(mapping_path);
  CheckMappingKeys(mapping, "", {"format", "imu", "wheels", "gps"}, mapping_path);
  if (!mapping["format"] || mapping["format"].as<std::string>() != "ros1_bag") {
    throw InputError(mapping_path, 0, "format", "", "expected 'ros1_bag' for a ROS bag");
  }
  const YAML::Node imu_map = mapping["imu"], wheel_map = mapping["wheels"],
                   gps_map = mapping["gps"];
  if (imu_map) {
    CheckMappingKeys(imu_map, "imu", {"topic", "body_from_sensor", "attitude", "yaw_offset"},
                     mapping_path);
  }
  if (wheel_map) {
    CheckMappingKeys(wheel_map, "wheels", {"topic", "from", "track", "radius"}, mapping_path);
    if (Text(wheel_map, "from", mapping_path, "wheels") != "body_twist") {
      throw InputError(mapping_path, 0, "wheels.from", "", "only 'body_twist' is supported");
    }
  }
  if (gps_map) CheckMappingKeys(gps_map, "gps", {"topic", "sd_v"}, mapping_path);
  const Eigen::Matrix3d body_from_sensor =
      imu_map ? Rotation(imu_map["body_from_sensor"], mapping_path) : Eigen::Matrix3d::Identity();
  const bool attitude = imu_map && imu_map["attitude"] && imu_map["attitude"].as<bool>();
  const double yaw_offset =
      imu_map && imu_map["yaw_offset"] ? imu_map["yaw_offset"].as<double>() : 0.0;
  const std::string imu_topic = imu_map ? Text(imu_map, "topic", mapping_path, "imu") : "";
  const std::string wheel_topic = wheel_map ? Text(wheel_map, "topic", mapping_path, "wheels") : "";
  const std::string gps_topic = gps_map ? Text(gps_map, "topic", mapping_path, "gps") : "";
  const double track = wheel_map ? Number(wheel_map, "track", mapping_path, "wheels") : 0.0;
  const double radius = wheel_map ? Number(wheel_map, "radius", mapping_path, "wheels") : 0.0;
  if (wheel_map && !(radius > 0.0 && track > 0.0)) {
    throw InputError(mapping_path, 0, "wheels.radius", "", "radius and track must be > 0");
  }

  DriveLog log;
  log.vehicle = vehicle;
  long imu_n = 0, wheel_n = 0, gps_n = 0, skipped = 0;
  std::vector<double> fix_t, fix_lat, fix_lon, fix_alt, fix_sd;
  try {
    CheckRosBagRecords(bag_path);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    std::vector<std::string> topics;
    for (const std::string& t : {imu_topic, wheel_topic, gps_topic}) {
      if (!t.empty()) topics.push_back(t);
    }
    rosbag::View view(bag, rosbag::TopicQuery(topics));
    for (const rosbag::MessageInstance& m : view) {
      const std::string& topic = m.getTopic();
      if (topic == imu_topic) {
        const sensor_msgs::Imu::ConstPtr imu = Decode<sensor_msgs::Imu>(m, bag_path);
        if (!imu) throw InputError(bag_path, 0, topic, m.getDataType(), "not a sensor_msgs/Imu");
        const Eigen::Vector3d f = body_from_sensor * Eigen::Vector3d(imu->linear_acceleration.x,
                                                                     imu->linear_acceleration.y,
                                                                     imu->linear_acceleration.z);
        const Eigen::Vector3d w =
            body_from_sensor * Eigen::Vector3d(imu->angular_velocity.x, imu->angular_velocity.y,
                                               imu->angular_velocity.z);
        const double t = imu->header.stamp.toSec();
        log.imu.push_back({t, f.x(), f.y(), f.z(), w.x(), w.y(), w.z()});
        ++imu_n;
        if (attitude) {
          const Eigen::Quaterniond q(imu->orientation.w, imu->orientation.x, imu->orientation.y,
                                     imu->orientation.z);
          if (q.norm() < 0.5) {
            ++skipped;
            continue;
          }
          // World from body = world from sensor x sensor from body.
          const Eigen::Matrix3d r =
              q.normalized().toRotationMatrix() * body_from_sensor.transpose();
          AttitudeSample a;
          a.t = t;
          a.yaw = std::remainder(std::atan2(r(1, 0), r(0, 0)) + yaw_offset, 2.0 * M_PI);
          a.pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
          a.roll = std::atan2(r(2, 1), r(2, 2));
          const auto& cov = imu->orientation_covariance;
          const auto sd = [&](int i) {
            return cov[4 * i] > 0.0 ? std::sqrt(cov[4 * i]) : kMissing;
          };
          a.sd_roll = sd(0), a.sd_pitch = sd(1), a.sd_yaw = sd(2);
          log.attitude.push_back(a);
        }
      } else if (topic == wheel_topic) {
        const nav_msgs::Odometry::ConstPtr odom = Decode<nav_msgs::Odometry>(m, bag_path);
        if (!odom) throw InputError(bag_path, 0, topic, m.getDataType(), "not a nav_msgs/Odometry");
        const double v = odom->twist.twist.linear.x, wz = odom->twist.twist.angular.z;
        WheelSample s;
        s.t = odom->header.stamp.toSec();
        s.omega_radps.fill(kMissing);
        s.omega_radps[0] = (v - 0.5 * track * wz) / radius;
        s.omega_radps[1] = (v + 0.5 * track * wz) / radius;
        log.wheels.push_back(s);
        ++wheel_n;
      } else if (topic == gps_topic) {
        const sensor_msgs::NavSatFix::ConstPtr fix = Decode<sensor_msgs::NavSatFix>(m, bag_path);
        if (!fix) {
          throw InputError(bag_path, 0, topic, m.getDataType(), "not a sensor_msgs/NavSatFix");
        }
        if (fix->status.status < sensor_msgs::NavSatStatus::STATUS_FIX ||
            !std::isfinite(fix->latitude) || !std::isfinite(fix->longitude)) {
          ++skipped;
          continue;
        }
        fix_t.push_back(fix->header.stamp.toSec());
        fix_lat.push_back(fix->latitude), fix_lon.push_back(fix->longitude);
        fix_alt.push_back(fix->altitude);
        fix_sd.push_back(fix->position_covariance_type > 0 && fix->position_covariance[0] > 0.0
                             ? std::sqrt(fix->position_covariance[0])
                             : kMissing);
        ++gps_n;
      }
    }
  } catch (const ros::Exception& e) {  // rosbag's and the deserializers' errors
    throw InputError(bag_path, 0, "", "", std::string("ROS bag: ") + e.what());
  }
  for (const auto& [key, topic, count] :
       {std::tuple<const char*, std::string, long>{"imu.topic", imu_topic, imu_n},
        {"wheels.topic", wheel_topic, wheel_n},
        {"gps.topic", gps_topic, gps_n}}) {
    if (!topic.empty() && count == 0) {
      throw InputError(mapping_path, 0, key, topic,
                       "no messages on this topic in " + bag_path +
                           " (`slipgraph import --list` shows the bag's topics)");
    }
  }
  if (!log.imu.empty()) log.present_files.push_back("imu.csv");
  if (!log.attitude.empty()) log.present_files.push_back("attitude.csv");
  if (!log.wheels.empty()) log.present_files.push_back("wheels.csv");
  if (imu_map) {
    report->lines.push_back("imu: " + std::to_string(imu_n) + " messages from " + imu_topic +
                            (attitude ? ", attitude from their orientation (yaw + " +
                                            std::to_string(yaw_offset) + " rad)"
                                      : "") +
                            ", rotated by body_from_sensor");
  }
  if (wheel_map) {
    report->lines.push_back("wheels: " + std::to_string(wheel_n) + " messages from " + wheel_topic +
                            ", side speeds from the body twist (track " + std::to_string(track) +
                            " m, radius " + std::to_string(radius) + " m)");
  }
  // GNSS: local ENU at the first fix on the WGS84 ellipsoid (NavSatFix's altitude is above it,
  // REP-145), velocity by central difference.
  if (!fix_t.empty()) {
    const GeographicLib::LocalCartesian local(fix_lat[0], fix_lon[0], fix_alt[0]);
    const double sd_v = MappingSd(gps_map, "gps", "sd_v", mapping_path);
    const size_t n = fix_t.size();
    std::vector<Eigen::Vector3d> enu(n);
    for (size_t i = 0; i < n; ++i) {
      local.Forward(fix_lat[i], fix_lon[i], fix_alt[i], enu[i].x(), enu[i].y(), enu[i].z());
    }
    for (size_t i = 0; i < n; ++i) {
      const size_t a = i > 0 ? i - 1 : i, b = i + 1 < n ? i + 1 : i;
      const double dt = fix_t[b] - fix_t[a];
      GpsSample g;
      g.t = fix_t[i];
      g.x = enu[i].x(), g.y = enu[i].y(), g.z = enu[i].z();
      const Eigen::Vector3d v =
          dt > 0.0 ? Eigen::Vector3d((enu[b] - enu[a]) / dt) : Eigen::Vector3d::Constant(kMissing);
      g.vx = v.x(), g.vy = v.y(), g.vz = v.z();
      g.sd_xy = fix_sd[i], g.sd_z = fix_sd[i], g.sd_v = sd_v;
      log.gps.push_back(g);
    }
    log.present_files.push_back("gps.csv");
    report->lines.push_back("gps: " + std::to_string(gps_n) + " fixes from " + gps_topic +
                            ", local ENU (WGS84) at the first fix, velocity by central "
                            "difference");
  }
  if (skipped > 0) {
    report->lines.push_back("skipped: " + std::to_string(skipped) +
                            " messages without a fix or an orientation");
  }
  double t0 = std::numeric_limits<double>::infinity();
  if (!log.imu.empty()) t0 = std::min(t0, log.imu.front().t);
  if (!log.wheels.empty()) t0 = std::min(t0, log.wheels.front().t);
  if (!log.gps.empty()) t0 = std::min(t0, log.gps.front().t);
  if (std::isfinite(t0)) {
    for (ImuSample& s : log.imu) s.t -= t0;
    for (AttitudeSample& s : log.attitude) s.t -= t0;
    for (WheelSample& s : log.wheels) s.t -= t0;
    for (GpsSample& s : log.gps) s.t -= t0;
    report->lines.push_back("time: header stamps, shifted by -" + std::to_string(t0) +
                            " s (the earliest)");
  }
  KeepReadableSamples(&log, report);
  return log;
}

}  // namespace

DriveLog ImportRosBag(const std::string& bag_path, const std::string& mapping_path,
                      const Vehicle& vehicle, ImportReport* report) {
  return NamingYamlErrors(mapping_path,
                          [&] { return Import(bag_path, mapping_path, vehicle, report); });
}

}  // namespace slipgraph
