// Import of ROS 2 bags into the drive-log format: a rosbag2 directory (metadata.yaml and its
// storage files) or one storage file, sqlite3 (.db3, sqlite_bag.h) or MCAP (.mcap, mcap_file.h),
// its messages in CDR (ros2_messages.h) turned into a log by ros_log_builder.h, whose header
// describes the mapping file.
#pragma once

#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/import_report.h"
#include "io/matlab_import.h"  // SourceEntry

namespace slipgraph {

// True when `path` is a directory holding a metadata.yaml or a .db3 / .mcap file, or is itself a
// SQLite or MCAP file.
bool IsRos2Bag(const std::string& path);

// The storage files of the bag at `path`, in recording order: those metadata.yaml's
// relative_file_paths lists, else every .db3 and .mcap file of the directory by name, else the
// file itself. Throws InputError when there is none or one is of another kind (a storage file
// compressed by rosbag2, .db3.zstd, has to be decompressed first).
std::vector<std::string> Ros2BagFiles(const std::string& path);

// Every topic of the bag with its message type, count and rate; `notes` (if given) gets what the
// readers noticed, such as a file cut short.
std::vector<SourceEntry> ListRos2Bag(const std::string& path,
                                     std::vector<std::string>* notes = nullptr);

// Throws InputError naming the mapping file and key, or the storage file, topic and stamp.
DriveLog ImportRos2Bag(const std::string& path, const std::string& mapping_path,
                       const Vehicle& vehicle, ImportReport* report);

}  // namespace slipgraph
