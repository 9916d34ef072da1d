// MCAP files (mcap.dev, the default storage of rosbag2 since ROS 2 Iron): the magic
// "\x89MCAP0\r\n", then records of an opcode (1 byte), a length (uint64) and the content, all
// little-endian; a Schema names a message type, a Channel a topic with its schema and encoding, a
// Message carries a channel id, a log time (ns) and the serialized bytes; a Chunk wraps records,
// uncompressed or compressed with zstd or lz4 (frame format; Debian's libzstd and liblz4). The
// data section is read from start to end, chunk by chunk (no index needed); the summary section
// after Data End is not read. A file cut short (a recording that stopped without closing it) is
// read up to its last whole record, and the reader says so.
#pragma once

#include <string>
#include <vector>

#include "io/bag_storage.h"

namespace slipgraph {

// True when the file starts with the MCAP magic.
bool IsMcapFile(const std::string& path);

// The file's topics with their counts and time spans; `*cut_short` (if given) is set to a
// description of where the file ends early, or "" when it is whole. Throws InputError naming the
// file and the byte offset when a record is malformed or a chunk does not decompress.
std::vector<BagTopic> ListMcap(const std::string& path, std::string* cut_short = nullptr);

// Every message of `topics` in the file's order; errors and `cut_short` as above.
void ReadMcap(const std::string& path, const std::vector<std::string>& topics,
              const BagMessageVisitor& visit, std::string* cut_short = nullptr);

}  // namespace slipgraph
