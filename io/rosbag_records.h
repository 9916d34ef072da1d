// The record structure of a ROS 1 bag (format 2.0), checked before the rosbag library reads it.
// That library trusts every length it reads: a corrupted or truncated bag made it allocate the
// 32-bit length it found (2.3 GB for a 71 kB file). Each record is a header length, the header
// (fields of a length and "name=value"), a data length and the data; an uncompressed chunk holds
// records of the same form.
#pragma once

#include <string>

namespace slipgraph {

// Throws InputError naming the file and the record's byte offset when the file does not start
// with the bag's version line, or a record or header field claims more bytes than its file or
// chunk holds (a bag cut short, or corrupted).
void CheckRosBagRecords(const std::string& path);

}  // namespace slipgraph
