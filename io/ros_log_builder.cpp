#include "io/ros_log_builder.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

#include "io/input_error.h"
#include "io/mapping_file.h"
#include "io/yaml_errors.h"

namespace slipgraph {
namespace {

int Line(const YAML::Node& node) { return node.Mark().is_null() ? 0 : node.Mark().line + 1; }

std::string Text(const YAML::Node& node, const std::string& key, const std::string& path,
                 const std::string& section) {
  if (!node[key]) throw InputError(path, Line(node), section + "." + key, "", "missing key");
  return node[key].as<std::string>();
}

double Number(const YAML::Node& node, const std::string& key, const std::string& path,
              const std::string& section) {
  if (!node[key]) throw InputError(path, Line(node), section + "." + key, "", "missing key");
  return node[key].as<double>();
}

std::array<double, 9> Rotation(const YAML::Node& node, const std::string& path) {
  const auto fail = [&](const std::string& what) {
    throw InputError(path, Line(node), "imu.body_from_sensor", "", what);
  };
  if (!node.IsSequence() || node.size() != 3) fail("expected 3 rows of 3 numbers");
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    if (!node[r].IsSequence() || node[r].size() != 3) fail("expected 3 rows of 3 numbers");
    for (int c = 0; c < 3; ++c) m(r, c) = node[r][c].as<double>();
  }
  if (!(m * m.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || m.determinant() < 0.0) {
    fail("not a rotation (orthonormal, determinant +1)");
  }
  std::array<double, 9> out;
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(out.data()) = m;
  return out;
}

// A list of joint names, or one name.
std::vector<std::string> Names(const YAML::Node& node) {
  if (node.IsScalar()) return {node.as<std::string>()};
  return node.as<std::vector<std::string>>();
}

RosMapping Read(const std::string& path, RosBagKind kind, const Vehicle& vehicle) {
  const YAML::Node root = LoadYamlFile(path);
  CheckMappingKeys(root, "", {"format", "imu", "wheels", "gps", "tf_topic"}, path);
  RosMapping m;
  m.path = path;
  m.format = root["format"] ? root["format"].as<std::string>() : "";
  const bool accepted = m.format == "ros_bag" ||
                        (m.format == "ros1_bag" && kind == RosBagKind::kRos1) ||
                        (m.format == "ros2_bag" && kind == RosBagKind::kRos2);
  if (!accepted) {
    throw InputError(path, root["format"] ? Line(root["format"]) : 0, "format", m.format,
                     std::string("expected 'ros_bag' or '") +
                         (kind == RosBagKind::kRos1 ? "ros1_bag" : "ros2_bag") +
                         "' for this recording (a " +
                         (kind == RosBagKind::kRos1 ? "ROS 1" : "ROS 2") + " bag)");
  }
  m.tf_topic = root["tf_topic"] ? root["tf_topic"].as<std::string>() : "/tf_static";
  if (const YAML::Node imu = root["imu"]) {
    CheckMappingKeys(imu, "imu",
                     {"topic", "body_from_sensor", "body_frame", "attitude", "yaw_offset"}, path);
    m.imu_topic = Text(imu, "topic", path, "imu");
    if (imu["body_from_sensor"] && imu["body_frame"]) {
      throw InputError(path, Line(imu["body_frame"]), "imu.body_frame", "",
                       "give body_from_sensor or body_frame, not both");
    }
    if (imu["body_from_sensor"]) m.body_from_sensor = Rotation(imu["body_from_sensor"], path);
    if (imu["body_frame"]) {
      m.imu_from_tf = true;
      m.body_frame = imu["body_frame"].as<std::string>();
    }
    m.attitude = imu["attitude"] && imu["attitude"].as<bool>();
    m.yaw_offset_rad = imu["yaw_offset"] ? imu["yaw_offset"].as<double>() : 0.0;
  }
  if (const YAML::Node wheels = root["wheels"]) {
    CheckMappingKeys(wheels, "wheels", {"topic", "from", "track", "radius", "joints", "signs"},
                     path);
    m.wheel_topic = Text(wheels, "topic", path, "wheels");
    m.wheels_from = Text(wheels, "from", path, "wheels");
    if (m.wheels_from == "body_twist") {
      CheckMappingKeys(wheels, "wheels", {"topic", "from", "track", "radius"}, path);
      m.track_m = Number(wheels, "track", path, "wheels");
      m.radius_m = Number(wheels, "radius", path, "wheels");
      if (!(m.radius_m > 0.0 && m.track_m > 0.0)) {
        throw InputError(path, Line(wheels), "wheels.radius", "", "radius and track must be > 0");
      }
    } else if (m.wheels_from == "joint_state") {
      CheckMappingKeys(wheels, "wheels", {"topic", "from", "joints", "signs"}, path);
      const std::vector<std::string>& names = WheelNames(vehicle.type);
      if (!wheels["joints"])
        throw InputError(path, Line(wheels), "wheels.joints", "", "missing key");
      CheckMappingKeys(wheels["joints"], "wheels.joints", names, path);
      if (wheels["signs"]) CheckMappingKeys(wheels["signs"], "wheels.signs", names, path);
      for (const std::string& name : names) {
        const YAML::Node joints = wheels["joints"][name];
        if (!joints) {
          throw InputError(path, Line(wheels["joints"]), "wheels.joints." + name, "",
                           "missing: every wheel of the vehicle needs its joints");
        }
        m.wheel_joints.push_back(Names(joints));
        if (m.wheel_joints.back().empty()) {
          throw InputError(path, Line(joints), "wheels.joints." + name, "", "no joint named");
        }
        const double sign =
            wheels["signs"] && wheels["signs"][name] ? wheels["signs"][name].as<double>() : 1.0;
        if (sign != 1.0 && sign != -1.0) {
          throw InputError(path, Line(wheels["signs"]), "wheels.signs." + name, "",
                           "expected 1 or -1");
        }
        m.wheel_signs.push_back(sign);
      }
    } else {
      throw InputError(path, Line(wheels["from"]), "wheels.from", m.wheels_from,
                       "expected 'body_twist' or 'joint_state'");
    }
  }
  if (const YAML::Node gps = root["gps"]) {
    CheckMappingKeys(gps, "gps", {"topic", "sd_v"}, path);
    m.gps_topic = Text(gps, "topic", path, "gps");
    m.gps_sd_v = MappingSd(gps, "gps", "sd_v", path);
  }
  return m;
}

// Rotation of an xyzw quaternion; a quaternion far from unit length is no rotation.
bool ToRotation(const std::array<double, 4>& q_xyzw, Eigen::Matrix3d* r) {
  const Eigen::Quaterniond q(q_xyzw[3], q_xyzw[0], q_xyzw[1], q_xyzw[2]);
  if (!(q.norm() > 0.5 && q.norm() < 2.0)) return false;
  *r = q.normalized().toRotationMatrix();
  return true;
}

}  // namespace

std::vector<std::string> RosMapping::topics() const {
  std::vector<std::string> out;
  for (const std::string& t : {imu_topic, wheel_topic, gps_topic}) {
    if (!t.empty()) out.push_back(t);
  }
  if (imu_from_tf) out.push_back(tf_topic);
  return out;
}

RosMapping ReadRosMapping(const std::string& mapping_path, RosBagKind kind,
                          const Vehicle& vehicle) {
  return NamingYamlErrors(mapping_path, [&] { return Read(mapping_path, kind, vehicle); });
}

RosLogBuilder::RosLogBuilder(RosMapping mapping, const Vehicle& vehicle, std::string source_path)
    : mapping_(std::move(mapping)), vehicle_(vehicle), source_path_(std::move(source_path)) {}

void RosLogBuilder::Add(const std::string& topic, const RosMessage& message) {
  const auto wrong = [&](const char* needed) {
    const double t = std::visit(
        [](const auto& m) {
          if constexpr (std::is_same_v<std::decay_t<decltype(m)>, RosTfMessage>) {
            return 0.0;
          } else {
            return m.stamp_s;
          }
        },
        message);
    throw InputError(source_path_, 0, topic, RosTimeText(t), std::string("not a ") + needed);
  };
  if (topic == mapping_.imu_topic) {
    if (!std::holds_alternative<RosImu>(message)) wrong(kRosImuType);
    imu_.push_back(std::get<RosImu>(message));
  }
  if (topic == mapping_.wheel_topic) {
    if (mapping_.wheels_from == "body_twist") {
      if (!std::holds_alternative<RosOdometry>(message)) wrong(kRosOdometryType);
      odometry_.push_back(std::get<RosOdometry>(message));
    } else {
      if (!std::holds_alternative<RosJointState>(message)) wrong(kRosJointStateType);
      joints_.push_back(std::get<RosJointState>(message));
    }
  }
  if (topic == mapping_.gps_topic) {
    if (!std::holds_alternative<RosNavSatFix>(message)) wrong(kRosNavSatFixType);
    fixes_.push_back(std::get<RosNavSatFix>(message));
  }
  if (mapping_.imu_from_tf && topic == mapping_.tf_topic) {
    if (!std::holds_alternative<RosTfMessage>(message)) wrong(kRosTfMessageType);
    const std::vector<RosTransform>& tfs = std::get<RosTfMessage>(message).transforms;
    static_transforms_.insert(static_transforms_.end(), tfs.begin(), tfs.end());
  }
}

namespace {

std::string Frame(const std::string& name) {
  return !name.empty() && name[0] == '/' ? name.substr(1) : name;
}

// The rotation of `frame` in the root of its tree of static transforms (p_root = R p_frame), and
// that root's name.
std::pair<std::string, Eigen::Matrix3d> InRoot(
    const std::map<std::string, std::pair<std::string, Eigen::Matrix3d>>& parent_of,
    const std::string& frame) {
  std::string at = frame;
  Eigen::Matrix3d root_from_frame = Eigen::Matrix3d::Identity();
  for (size_t step = 0; step <= parent_of.size(); ++step) {
    const auto it = parent_of.find(at);
    if (it == parent_of.end()) return {at, root_from_frame};
    root_from_frame = it->second.second * root_from_frame;
    at = it->second.first;
  }
  return {"", root_from_frame};  // a cycle: no root
}

}  // namespace

DriveLog RosLogBuilder::Finish(ImportReport* report) {
  const RosMapping& m = mapping_;
  const std::string list_hint =
      " (`slipgraph import --list` shows the recording's topics and types)";
  for (const auto& [key, topic, count] :
       {std::tuple<const char*, std::string, size_t>{"imu.topic", m.imu_topic, imu_.size()},
        {"wheels.topic", m.wheel_topic, odometry_.size() + joints_.size()},
        {"gps.topic", m.gps_topic, fixes_.size()}}) {
    if (!topic.empty() && count == 0) {
      throw InputError(m.path, 0, key, topic,
                       "no messages on this topic in " + source_path_ + list_hint);
    }
  }
  Eigen::Matrix3d body_from_sensor =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m.body_from_sensor.data());
  std::string mounting = "rotated by body_from_sensor";
  if (m.imu_from_tf && !imu_.empty()) {
    const std::string sensor = Frame(imu_.front().frame_id);
    if (sensor.empty()) {
      throw InputError(m.path, 0, "imu.body_frame", m.body_frame,
                       "the IMU messages name no frame_id: give body_from_sensor instead");
    }
    std::map<std::string, std::pair<std::string, Eigen::Matrix3d>> parent_of;
    for (const RosTransform& tf : static_transforms_) {
      Eigen::Matrix3d r;
      if (!ToRotation(tf.rotation_xyzw, &r)) {
        throw InputError(source_path_, 0, m.tf_topic, tf.parent_frame + " -> " + tf.child_frame,
                         "the transform's rotation is not a unit quaternion");
      }
      parent_of[Frame(tf.child_frame)] = {Frame(tf.parent_frame), r};
    }
    const auto [body_root, root_from_body] = InRoot(parent_of, Frame(m.body_frame));
    const auto [sensor_root, root_from_sensor] = InRoot(parent_of, sensor);
    if (body_root.empty() || body_root != sensor_root) {
      throw InputError(m.path, 0, "imu.body_frame", m.body_frame,
                       "no chain of static transforms on " + m.tf_topic + " in " + source_path_ +
                           " joins this frame to the IMU's frame '" + sensor + "' (" +
                           std::to_string(static_transforms_.size()) + " transforms)");
    }
    body_from_sensor = root_from_body.transpose() * root_from_sensor;
    mounting = "mounting from " + m.tf_topic + " (" + m.body_frame + " <- " + sensor + ")";
  }

  DriveLog log;
  log.vehicle = vehicle_;
  long skipped = 0;
  for (const RosImu& imu : imu_) {
    const Eigen::Vector3d f = body_from_sensor * Eigen::Vector3d(imu.linear_acceleration.data());
    const Eigen::Vector3d w = body_from_sensor * Eigen::Vector3d(imu.angular_velocity.data());
    log.imu.push_back({imu.stamp_s, f.x(), f.y(), f.z(), w.x(), w.y(), w.z()});
    if (!m.attitude) continue;
    Eigen::Matrix3d world_from_sensor;
    if (!ToRotation(imu.orientation_xyzw, &world_from_sensor)) {
      ++skipped;
      continue;
    }
    // World from body = world from sensor x sensor from body.
    const Eigen::Matrix3d r = world_from_sensor * body_from_sensor.transpose();
    AttitudeSample a;
    a.t = imu.stamp_s;
    a.yaw = std::remainder(std::atan2(r(1, 0), r(0, 0)) + m.yaw_offset_rad, 2.0 * M_PI);
    a.pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
    a.roll = std::atan2(r(2, 1), r(2, 2));
    const auto sd = [&](int i) {
      const double var = imu.orientation_covariance[4 * i];
      return var > 0.0 ? std::sqrt(var) : kMissing;
    };
    a.sd_roll = sd(0), a.sd_pitch = sd(1), a.sd_yaw = sd(2);
    log.attitude.push_back(a);
  }
  for (const RosOdometry& odom : odometry_) {
    const double v = odom.linear[0], wz = odom.angular[2];
    WheelSample s;
    s.t = odom.stamp_s;
    s.omega_radps.fill(kMissing);
    s.omega_radps[0] = (v - 0.5 * m.track_m * wz) / m.radius_m;
    s.omega_radps[1] = (v + 0.5 * m.track_m * wz) / m.radius_m;
    log.wheels.push_back(s);
  }
  long joints_missing = 0;
  for (const RosJointState& js : joints_) {
    WheelSample s;
    s.t = js.stamp_s;
    s.omega_radps.fill(kMissing);
    for (size_t wheel = 0; wheel < m.wheel_joints.size(); ++wheel) {
      double sum = 0.0;
      int n = 0;
      for (const std::string& joint : m.wheel_joints[wheel]) {
        const auto it = std::find(js.name.begin(), js.name.end(), joint);
        const size_t i = static_cast<size_t>(it - js.name.begin());
        if (it != js.name.end() && i < js.velocity.size()) sum += js.velocity[i], ++n;
      }
      if (n == static_cast<int>(m.wheel_joints[wheel].size())) {
        s.omega_radps[wheel] = m.wheel_signs[wheel] * sum / n;
      } else {
        ++joints_missing;
      }
    }
    log.wheels.push_back(s);
  }
  std::vector<const RosNavSatFix*> fixes;
  for (const RosNavSatFix& fix : fixes_) {
    if (fix.status < 0 || !std::isfinite(fix.latitude_deg) || !std::isfinite(fix.longitude_deg)) {
      ++skipped;
      continue;
    }
    fixes.push_back(&fix);
  }
  // Storage order need not be time order: the origin and the central differences need it.
  std::stable_sort(fixes.begin(), fixes.end(), [](const RosNavSatFix* a, const RosNavSatFix* b) {
    return a->stamp_s < b->stamp_s;
  });
  if (!m.gps_topic.empty() && fixes.empty()) {
    throw InputError(m.path, 0, "gps.topic", m.gps_topic,
                     "no message on this topic in " + source_path_ + " has a fix");
  }
  if (!log.imu.empty()) log.present_files.push_back("imu.csv");
  if (!log.attitude.empty()) log.present_files.push_back("attitude.csv");
  if (!log.wheels.empty()) log.present_files.push_back("wheels.csv");
  if (!m.imu_topic.empty()) {
    report->lines.push_back("imu: " + std::to_string(imu_.size()) + " messages from " +
                            m.imu_topic +
                            (m.attitude ? ", attitude from their orientation (yaw + " +
                                              std::to_string(m.yaw_offset_rad) + " rad)"
                                        : "") +
                            ", " + mounting);
  }
  if (m.wheels_from == "body_twist") {
    report->lines.push_back("wheels: " + std::to_string(odometry_.size()) + " messages from " +
                            m.wheel_topic + ", side speeds from the body twist (track " +
                            std::to_string(m.track_m) + " m, radius " + std::to_string(m.radius_m) +
                            " m)");
  } else if (m.wheels_from == "joint_state") {
    std::string which;
    const std::vector<std::string>& names = WheelNames(vehicle_.type);
    for (size_t wheel = 0; wheel < m.wheel_joints.size(); ++wheel) {
      which += (wheel ? "; " : "") + names[wheel] + " =" + (m.wheel_signs[wheel] < 0 ? " -" : "") +
               " mean of";
      for (const std::string& joint : m.wheel_joints[wheel]) which += " " + joint;
    }
    report->lines.push_back("wheels: " + std::to_string(joints_.size()) + " messages from " +
                            m.wheel_topic + ", joint velocities (" + which + ")");
    if (joints_missing > 0) {
      report->lines.push_back("wheels: " + std::to_string(joints_missing) +
                              " wheel readings missing (a message without all of a wheel's "
                              "joints or their velocities)");
    }
  }
  // GNSS: local ENU at the first fix on the WGS84 ellipsoid (NavSatFix's altitude is above it,
  // REP-145), velocity by central difference.
  if (!fixes.empty()) {
    const RosNavSatFix& first = *fixes.front();
    const GeographicLib::LocalCartesian local(first.latitude_deg, first.longitude_deg,
                                              first.altitude_m);
    const size_t n = fixes.size();
    std::vector<Eigen::Vector3d> enu(n);
    for (size_t i = 0; i < n; ++i) {
      local.Forward(fixes[i]->latitude_deg, fixes[i]->longitude_deg, fixes[i]->altitude_m,
                    enu[i].x(), enu[i].y(), enu[i].z());
    }
    for (size_t i = 0; i < n; ++i) {
      const size_t a = i > 0 ? i - 1 : i, b = i + 1 < n ? i + 1 : i;
      const double dt = fixes[b]->stamp_s - fixes[a]->stamp_s;
      GpsSample g;
      g.t = fixes[i]->stamp_s;
      g.x = enu[i].x(), g.y = enu[i].y(), g.z = enu[i].z();
      const Eigen::Vector3d v =
          dt > 0.0 ? Eigen::Vector3d((enu[b] - enu[a]) / dt) : Eigen::Vector3d::Constant(kMissing);
      g.vx = v.x(), g.vy = v.y(), g.vz = v.z();
      const RosNavSatFix& fix = *fixes[i];
      const double sd = fix.position_covariance_type > 0 && fix.position_covariance[0] > 0.0
                            ? std::sqrt(fix.position_covariance[0])
                            : kMissing;
      g.sd_xy = sd, g.sd_z = sd, g.sd_v = m.gps_sd_v;
      log.gps.push_back(g);
    }
    log.present_files.push_back("gps.csv");
    report->lines.push_back("gps: " + std::to_string(n) + " fixes from " + m.gps_topic +
                            ", local ENU (WGS84) at the first fix, velocity by central "
                            "difference");
  }
  if (skipped > 0) {
    report->lines.push_back("skipped: " + std::to_string(skipped) +
                            " messages without a fix or an orientation");
  }
  double t0 = std::numeric_limits<double>::infinity();  // storage order need not be time order
  for (const ImuSample& s : log.imu) t0 = std::min(t0, s.t);
  for (const WheelSample& s : log.wheels) t0 = std::min(t0, s.t);
  for (const GpsSample& s : log.gps) t0 = std::min(t0, s.t);
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

}  // namespace slipgraph
