// The ROS 2 messages of ros_messages.h decoded from their CDR bytes (cdr_reader.h), field by
// field in the order of their .msg definitions (std_msgs/Header: builtin_interfaces/Time stamp
// {int32 sec, uint32 nanosec}, string frame_id).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "io/ros_messages.h"

namespace slipgraph {

// A ROS 2 type name ("sensor_msgs/msg/Imu") as ROS 1 writes it ("sensor_msgs/Imu").
std::string RosTypeWithoutMsg(const std::string& type);

// The message of type `type` (either spelling), or nullopt for a type the importer does not
// read. Throws CdrError when the bytes do not decode as the type.
std::optional<RosMessage> DecodeRos2Message(const std::string& type, const uint8_t* data,
                                            size_t size);

}  // namespace slipgraph
