// The builder that turns ROS messages into a drive log, on messages made here: wheel speeds from
// sensor_msgs/JointState (joints averaged per wheel, signs, a message without a wheel's joint);
// the IMU's mounting from static transforms equal to the one stated as body_from_sensor; and the
// mapping's errors, each naming the file and the key.
#include "io/ros_log_builder.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "io/input_error.h"
#include "tests/import_test_util.h"
#include "tests/tiny_recordings.h"

namespace slipgraph {
namespace {

std::string Mapping(const std::string& name, const std::string& text) {
  return testing::WriteText(::testing::TempDir(), name, text);
}

std::array<double, 4> Xyzw(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  return {q.x(), q.y(), q.z(), q.w()};
}

TEST(RosLogBuilder, WheelSpeedsFromJointStates) {
  const Vehicle vehicle = testing::TinyVehicle();  // left, right
  const std::string path = Mapping("joints.yaml",
                                   "format: ros2_bag\n"
                                   "wheels:\n"
                                   "  topic: /joint_states\n"
                                   "  from: joint_state\n"
                                   "  joints: {left: [fl, rl], right: fr}\n"
                                   "  signs: {left: -1}\n");
  RosLogBuilder builder(ReadRosMapping(path, RosBagKind::kRos2, vehicle), vehicle, "bag");
  for (int i = 0; i < 10; ++i) {
    RosJointState js;
    js.stamp_s = 100.0 + 0.1 * i;
    js.name = {"fr", "rl", "fl", "caster"};
    js.velocity = {5.0, -4.0, -6.0, 99.0};
    if (i == 9) js.name[0] = "other";  // the right wheel's joint missing
    builder.Add("/joint_states", js);
  }
  ImportReport report;
  const DriveLog log = builder.Finish(&report);
  ASSERT_EQ(log.wheels.size(), 9u);  // the last one lost its right wheel: not readable
  EXPECT_NEAR(log.wheels[3].t, 0.3, 1e-9);
  EXPECT_EQ(log.wheels[3].omega_radps[0], 5.0);  // -(-6 + -4) / 2
  EXPECT_EQ(log.wheels[3].omega_radps[1], 5.0);
  bool said = false;
  for (const std::string& line : report.lines) {
    said = said || line.find("1 wheel readings missing") != std::string::npos;
  }
  EXPECT_TRUE(said);
}

TEST(RosLogBuilder, MountingFromStaticTransformsEqualsTheStatedRotation) {
  const Vehicle vehicle = testing::TinyVehicle();
  Eigen::Matrix3d body_from_sensor;
  body_from_sensor << 0, 0, -1, -1, 0, 0, 0, 1, 0;  // kBagMapping's
  // base_link <- mount (yawed and pitched) <- imu_link, plus a branch that is not on the way.
  const Eigen::Matrix3d body_from_mount = (Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()) *
                                           Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()))
                                              .toRotationMatrix();
  RosTfMessage tf;
  tf.transforms.push_back({"base_link", "mount", {0.1, 0, 0.3}, Xyzw(body_from_mount)});
  tf.transforms.push_back(
      {"mount", "/imu_link", {0, 0, 0}, Xyzw(body_from_mount.transpose() * body_from_sensor)});
  tf.transforms.push_back({"base_link", "gps", {0, 0, 1}, Xyzw(Eigen::Matrix3d::Identity())});
  const std::string stated = Mapping("stated.yaml",
                                     "format: ros_bag\n"
                                     "imu: {topic: /imu, body_from_sensor: [[0, 0, -1], [-1, 0, "
                                     "0], [0, 1, 0]], attitude: true}\n");
  const std::string from_tf =
      Mapping("from_tf.yaml",
              "format: ros_bag\nimu: {topic: /imu, body_frame: base_link, attitude: true}\n");
  std::vector<DriveLog> logs;
  for (const std::string& path : {stated, from_tf}) {
    RosLogBuilder builder(ReadRosMapping(path, RosBagKind::kRos1, vehicle), vehicle, "bag");
    for (int i = 0; i < 5; ++i) {
      RosImu imu;
      imu.stamp_s = 0.02 * i, imu.frame_id = "imu_link";
      imu.linear_acceleration = {-0.1, 9.8, -0.3};
      imu.angular_velocity = {0.0, 0.2, 0.0};
      imu.orientation_xyzw = Xyzw(body_from_sensor);  // the body level, yaw 0
      builder.Add("/imu", imu);
      if (i == 2) builder.Add("/tf_static", tf);  // after the first IMU messages
    }
    ImportReport report;
    logs.push_back(builder.Finish(&report));
  }
  ASSERT_EQ(logs[1].imu.size(), 5u);
  EXPECT_NEAR(logs[1].imu[3].ax, 0.3, 1e-12);
  EXPECT_NEAR(logs[1].imu[3].ay, 0.1, 1e-12);
  EXPECT_NEAR(logs[1].imu[3].az, 9.8, 1e-12);
  EXPECT_NEAR(logs[1].imu[3].gz, 0.2, 1e-12);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(logs[1].imu[i].ax, logs[0].imu[i].ax, 1e-12);
    EXPECT_NEAR(logs[1].attitude[i].yaw, logs[0].attitude[i].yaw, 1e-12);
    EXPECT_NEAR(logs[1].attitude[i].pitch, 0.0, 1e-12);
  }

  // A frame the transforms do not join to the IMU's.
  const std::string no_chain =
      Mapping("no_chain.yaml", "format: ros_bag\nimu: {topic: /imu, body_frame: chassis}\n");
  RosLogBuilder builder(ReadRosMapping(no_chain, RosBagKind::kRos1, vehicle), vehicle, "bag");
  RosImu imu;
  imu.frame_id = "imu_link";
  builder.Add("/imu", imu);
  builder.Add("/tf_static", tf);
  ImportReport report;
  const std::string e = testing::ErrorOf([&] { builder.Finish(&report); });
  EXPECT_NE(e.find("imu.body_frame"), std::string::npos) << e;
  EXPECT_NE(e.find("imu_link"), std::string::npos) << e;
}

TEST(RosLogBuilder, MappingErrorsNameTheFileAndTheKey) {
  const Vehicle vehicle = testing::TinyVehicle();
  const auto error = [&](const std::string& text, RosBagKind kind = RosBagKind::kRos2) {
    const std::string path = Mapping("bad.yaml", text);
    return testing::ErrorOf([&] { ReadRosMapping(path, kind, vehicle); });
  };
  std::string e = error("format: ros1_bag\nimu: {topic: /imu}\n");
  EXPECT_NE(e.find("bad.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("'ros2_bag'"), std::string::npos) << e;
  e = error(
      "format: ros_bag\nimu: {topic: /imu, body_frame: base_link, body_from_sensor: "
      "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n");
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = error("format: ros_bag\nimu: {topic: /imu, body_from_sensor: [[1, 0, 0], [0, 1, 0]]}\n");
  EXPECT_NE(e.find("imu.body_from_sensor"), std::string::npos) << e;
  e = error("format: ros_bag\nwheels: {topic: /j, from: joint_state, joints: {left: a}}\n");
  EXPECT_NE(e.find("wheels.joints.right"), std::string::npos) << e;
  e = error(
      "format: ros_bag\nwheels: {topic: /j, from: joint_state, joints: {left: a, right: b, "
      "fl: c}}\n");
  EXPECT_NE(e.find("wheels.joints.fl"), std::string::npos) << e;
  e = error(
      "format: ros_bag\nwheels: {topic: /j, from: joint_state, joints: {left: a, right: b}, "
      "signs: {left: 2}}\n");
  EXPECT_NE(e.find("wheels.signs.left"), std::string::npos) << e;
  e = error("format: ros_bag\nwheels: {topic: /j, from: twist}\n");
  EXPECT_NE(e.find("wheels.from"), std::string::npos) << e;
  e = error(
      "format: ros_bag\nwheels: {topic: /j, from: body_twist, track: 0.5, radius: 0.1, "
      "joints: {left: a}}\n");
  EXPECT_NE(e.find("wheels.joints"), std::string::npos) << e;

  // A message of another type on a mapped topic names the topic and the stamp.
  const std::string path = Mapping("good.yaml", "format: ros_bag\ngps: {topic: /fix}\n");
  RosLogBuilder builder(ReadRosMapping(path, RosBagKind::kRos2, vehicle), vehicle, "the.mcap");
  RosOdometry odom;
  odom.stamp_s = 12.5;
  e = testing::ErrorOf([&] { builder.Add("/fix", odom); });
  EXPECT_NE(e.find("the.mcap"), std::string::npos) << e;
  EXPECT_NE(e.find("t=12.5"), std::string::npos) << e;
  EXPECT_NE(e.find("not a sensor_msgs/NavSatFix"), std::string::npos) << e;
}

}  // namespace
}  // namespace slipgraph
