#include "io/ros2_messages.h"

#include "io/cdr_reader.h"

namespace slipgraph {
namespace {

double Stamp(CdrReader& in) {
  const int32_t sec = in.I32();
  const uint32_t nanosec = in.U32();
  return sec + 1e-9 * nanosec;
}

// std_msgs/Header: the stamp, and the frame into `frame_id`.
double Header(CdrReader& in, std::string* frame_id) {
  const double t = Stamp(in);
  *frame_id = in.String();
  return t;
}

template <size_t N>
void Read(CdrReader& in, std::array<double, N>* out) {
  in.Doubles(out->data(), N);
}

RosImu Imu(CdrReader& in) {
  RosImu m;
  m.stamp_s = Header(in, &m.frame_id);
  Read(in, &m.orientation_xyzw);
  Read(in, &m.orientation_covariance);
  std::array<double, 9> unused;
  Read(in, &m.angular_velocity);
  Read(in, &unused);
  Read(in, &m.linear_acceleration);
  Read(in, &unused);
  return m;
}

RosOdometry Odometry(CdrReader& in) {
  RosOdometry m;
  std::string frame;
  m.stamp_s = Header(in, &frame);
  in.String();  // child_frame_id
  std::array<double, 7> pose;
  std::array<double, 36> covariance;
  Read(in, &pose);
  Read(in, &covariance);
  Read(in, &m.linear);
  Read(in, &m.angular);
  Read(in, &covariance);
  return m;
}

RosNavSatFix NavSatFix(CdrReader& in) {
  RosNavSatFix m;
  std::string frame;
  m.stamp_s = Header(in, &frame);
  m.status = in.I8();
  in.U16();  // service
  m.latitude_deg = in.F64();
  m.longitude_deg = in.F64();
  m.altitude_m = in.F64();
  Read(in, &m.position_covariance);
  m.position_covariance_type = in.U8();
  return m;
}

std::vector<double> DoubleSequence(CdrReader& in) {
  std::vector<double> out(in.SequenceLength(8));
  in.Doubles(out.data(), out.size());
  return out;
}

RosJointState JointState(CdrReader& in) {
  RosJointState m;
  std::string frame;
  m.stamp_s = Header(in, &frame);
  m.name.resize(in.SequenceLength(4));
  for (std::string& name : m.name) name = in.String();
  m.position = DoubleSequence(in);
  m.velocity = DoubleSequence(in);
  DoubleSequence(in);  // effort: read so that a message cut short is seen
  return m;
}

RosTfMessage TfMessage(CdrReader& in) {
  RosTfMessage m;
  // A TransformStamped takes at least 8 (stamp) + 4 + 4 (frames) + 56 (transform) bytes.
  m.transforms.resize(in.SequenceLength(72));
  for (RosTransform& tf : m.transforms) {
    Header(in, &tf.parent_frame);
    tf.child_frame = in.String();
    Read(in, &tf.translation);
    Read(in, &tf.rotation_xyzw);
  }
  return m;
}

}  // namespace

std::string RosTypeWithoutMsg(const std::string& type) {
  const size_t at = type.find("/msg/");
  return at == std::string::npos ? type : type.substr(0, at) + "/" + type.substr(at + 5);
}

std::optional<RosMessage> DecodeRos2Message(const std::string& type, const uint8_t* data,
                                            size_t size) {
  const std::string name = RosTypeWithoutMsg(type);
  if (name != kRosImuType && name != kRosOdometryType && name != kRosNavSatFixType &&
      name != kRosJointStateType && name != kRosTfMessageType) {
    return std::nullopt;
  }
  CdrReader in(data, size);
  if (name == kRosImuType) return Imu(in);
  if (name == kRosOdometryType) return Odometry(in);
  if (name == kRosNavSatFixType) return NavSatFix(in);
  if (name == kRosJointStateType) return JointState(in);
  return TfMessage(in);
}

}  // namespace slipgraph
