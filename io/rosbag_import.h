// Import of ROS 1 bags into the drive-log format, read with Debian's ROS bag libraries
// (librosbag-dev) and turned into a log by ros_log_builder.h, whose header describes the mapping
// file. The bag's record structure is checked first (rosbag_records.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/import_report.h"
#include "io/matlab_import.h"  // SourceEntry
#include "io/ros_messages.h"

namespace slipgraph {

// Throws InputError naming the mapping file and key, or the bag and topic.
DriveLog ImportRosBag(const std::string& bag_path, const std::string& mapping_path,
                      const Vehicle& vehicle, ImportReport* report);

// Each message of `topics` in the bag's order, decoded, with its topic and receive time (s); a
// type the importer does not read is an InputError naming it. Throws InputError as above.
void ForEachRosBagMessage(const std::string& bag_path, const std::vector<std::string>& topics,
                          const std::function<void(const std::string& topic, double time_s,
                                                   const RosMessage& message)>& visit);

// Every topic of a bag with its message type, count and rate. Throws InputError when the bag
// cannot be read.
std::vector<SourceEntry> ListRosBag(const std::string& bag_path);

// True when the file starts with the ROS 1 bag header ("#ROSBAG V2.0").
bool IsRosBag(const std::string& path);

}  // namespace slipgraph
