// What the readers of ROS 2 bag storage (sqlite_bag.h for rosbag2's sqlite3 files, mcap_file.h
// for MCAP) hand to the importer: the topics with their types, and the messages one by one with
// their serialized bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace slipgraph {

// One topic of a recording: its name, message type ("sensor_msgs/msg/Imu"), serialization
// ("cdr"), how many messages and the first and last of their receive times (ns).
struct BagTopic {
  std::string name, type, serialization;
  long count = 0;
  int64_t first_ns = 0, last_ns = 0;
};

// Called for each message of the topics asked for: its topic, receive time (ns) and bytes (valid
// during the call only).
using BagMessageVisitor =
    std::function<void(const BagTopic& topic, int64_t time_ns, const uint8_t* data, size_t size)>;

}  // namespace slipgraph
