// rosbag2's sqlite3 storage (a .db3 file, read with Debian's libsqlite3): a table `topics` (id,
// name, type, serialization_format, ...) and a table `messages` (id, topic_id, timestamp in ns,
// data as a BLOB of the serialized message). Opened read-only.
#pragma once

#include <string>
#include <vector>

#include "io/bag_storage.h"

namespace slipgraph {

// True when the file starts with SQLite's header ("SQLite format 3").
bool IsSqliteFile(const std::string& path);

// The file's topics with their counts and time spans. Throws InputError naming the file when it
// is not a readable rosbag2 database.
std::vector<BagTopic> ListSqliteBag(const std::string& path);

// Every message of `topics` in time order. Throws InputError naming the file as above.
void ReadSqliteBag(const std::string& path, const std::vector<std::string>& topics,
                   const BagMessageVisitor& visit);

}  // namespace slipgraph
