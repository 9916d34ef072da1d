// CDR reading and the ROS 2 messages decoded from it: each message type written field by field
// (tests/ros2_bag_writer.h) in both byte orders decodes to what was written; alignment counts
// from the end of the encapsulation header; bytes cut short, a sequence longer than the bytes and
// an encapsulation other than plain CDR are CdrErrors, never a read past the end.
#include "io/cdr_reader.h"

#include <gtest/gtest.h>

#include "io/ros2_messages.h"
#include "tests/ros2_bag_writer.h"

namespace slipgraph {
namespace {

using testing::CdrWriter;
using testing::EncodeRos2;

TEST(CdrReader, AlignsFromTheEndOfTheHeaderInBothByteOrders) {
  for (const bool little : {true, false}) {
    CdrWriter w(little);
    w.U8(7);
    w.F64(-2.5);  // 7 padding bytes before it: offset 8 after the header
    w.String("ab");
    w.U16(513);
    w.U32(70000);
    // u8 at 0, 7 pad, f64 at 8, length at 16, "ab\0" at 20, 1 pad, u16 at 24, 2 pad, u32 at 28.
    ASSERT_EQ(w.bytes().size(), 4u + 32);
    CdrReader r(w.bytes().data(), w.bytes().size());
    EXPECT_EQ(r.U8(), 7);
    EXPECT_EQ(r.F64(), -2.5);
    EXPECT_EQ(r.String(), "ab");
    EXPECT_EQ(r.U16(), 513);
    EXPECT_EQ(r.U32(), 70000u);
    EXPECT_THROW(r.U8(), CdrError);  // nothing left
  }
}

TEST(CdrReader, RejectsWhatIsNotPlainCdrOrEndsEarly) {
  const uint8_t xcdr2[] = {0, 7, 0, 0, 1, 2, 3, 4};
  EXPECT_THROW(CdrReader(xcdr2, sizeof(xcdr2)), CdrError);
  EXPECT_THROW(CdrReader(xcdr2, 3), CdrError);
  CdrWriter w;
  w.U32(1000000);  // a sequence of a million doubles in no bytes
  CdrReader r(w.bytes().data(), w.bytes().size());
  EXPECT_THROW(r.SequenceLength(8), CdrError);
}

TEST(Ros2Messages, EachTypeDecodesToWhatWasWrittenInBothByteOrders) {
  RosImu imu;
  imu.stamp_s = 1700000000.25, imu.frame_id = "imu_link";
  imu.orientation_xyzw = {0.1, 0.2, 0.3, 0.9};
  imu.orientation_covariance[4] = 0.01;
  imu.angular_velocity = {0.01, -0.02, 0.3}, imu.linear_acceleration = {0.5, -0.1, 9.81};
  RosOdometry odom;
  odom.stamp_s = 12.5, odom.linear = {1.0, 0.0, 0.0}, odom.angular = {0.0, 0.0, -0.2};
  RosNavSatFix fix;
  fix.stamp_s = 3.0, fix.status = -1, fix.latitude_deg = 45.1, fix.longitude_deg = -7.2;
  fix.altitude_m = 310.0, fix.position_covariance[0] = 4.0, fix.position_covariance_type = 2;
  RosJointState joints;
  joints.stamp_s = 4.0, joints.name = {"left_wheel", "right_wheel"};
  joints.position = {1.0, 2.0}, joints.velocity = {3.5, -3.25};
  RosTfMessage tf;
  tf.transforms.push_back({"base_link", "imu_link", {0.1, 0.0, 0.2}, {0.0, 0.0, 0.7071, 0.7071}});
  tf.transforms.push_back({"base_link", "gps", {0.0, 0.0, 0.5}, {0.0, 0.0, 0.0, 1.0}});
  for (const bool little : {true, false}) {
    const auto decode = [&](const RosMessage& m, const std::string& type) {
      const std::vector<uint8_t> bytes = EncodeRos2(m, little);
      const std::optional<RosMessage> out = DecodeRos2Message(type, bytes.data(), bytes.size());
      EXPECT_TRUE(out.has_value()) << type;
      // Cut short by one byte anywhere past the header, it throws.
      for (size_t n = 4; n < bytes.size(); n += 7) {
        EXPECT_THROW(DecodeRos2Message(type, bytes.data(), n), CdrError) << type << " " << n;
      }
      return out.value_or(RosMessage{});
    };
    const RosImu i = std::get<RosImu>(decode(imu, "sensor_msgs/msg/Imu"));
    EXPECT_EQ(i.stamp_s, imu.stamp_s);
    EXPECT_EQ(i.frame_id, "imu_link");
    EXPECT_EQ(i.orientation_xyzw, imu.orientation_xyzw);
    EXPECT_EQ(i.orientation_covariance, imu.orientation_covariance);
    EXPECT_EQ(i.angular_velocity, imu.angular_velocity);
    EXPECT_EQ(i.linear_acceleration, imu.linear_acceleration);
    const RosOdometry o = std::get<RosOdometry>(decode(odom, "nav_msgs/msg/Odometry"));
    EXPECT_EQ(o.linear, odom.linear);
    EXPECT_EQ(o.angular, odom.angular);
    const RosNavSatFix f = std::get<RosNavSatFix>(decode(fix, "sensor_msgs/msg/NavSatFix"));
    EXPECT_EQ(f.status, -1);
    EXPECT_EQ(f.latitude_deg, 45.1);
    EXPECT_EQ(f.longitude_deg, -7.2);
    EXPECT_EQ(f.altitude_m, 310.0);
    EXPECT_EQ(f.position_covariance, fix.position_covariance);
    EXPECT_EQ(f.position_covariance_type, 2);
    const RosJointState j = std::get<RosJointState>(decode(joints, "sensor_msgs/msg/JointState"));
    EXPECT_EQ(j.name, joints.name);
    EXPECT_EQ(j.velocity, joints.velocity);
    EXPECT_EQ(j.position, joints.position);
    // ROS 1 spelling of the type name is taken too.
    const RosTfMessage t = std::get<RosTfMessage>(decode(tf, "tf2_msgs/TFMessage"));
    ASSERT_EQ(t.transforms.size(), 2u);
    EXPECT_EQ(t.transforms[0].parent_frame, "base_link");
    EXPECT_EQ(t.transforms[0].child_frame, "imu_link");
    EXPECT_EQ(t.transforms[0].translation, tf.transforms[0].translation);
    EXPECT_EQ(t.transforms[0].rotation_xyzw, tf.transforms[0].rotation_xyzw);
    EXPECT_EQ(t.transforms[1].child_frame, "gps");
  }
}

TEST(Ros2Messages, ATypeNotReadIsNoMessageAndNoError) {
  const uint8_t garbage[] = {9, 9};
  EXPECT_FALSE(DecodeRos2Message("sensor_msgs/msg/Image", garbage, sizeof(garbage)).has_value());
  EXPECT_EQ(RosTypeWithoutMsg("sensor_msgs/msg/Imu"), "sensor_msgs/Imu");
  EXPECT_EQ(RosTypeWithoutMsg("sensor_msgs/Imu"), "sensor_msgs/Imu");
}

}  // namespace
}  // namespace slipgraph
