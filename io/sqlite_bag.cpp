#include "io/sqlite_bag.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>

#include "io/input_error.h"

namespace slipgraph {
namespace {

struct CloseDatabase {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct FinalizeStatement {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Database = std::unique_ptr<sqlite3, CloseDatabase>;
using Statement = std::unique_ptr<sqlite3_stmt, FinalizeStatement>;

[[noreturn]] void Fail(const std::string& path, sqlite3* db, const std::string& doing) {
  throw InputError(path, 0, "", "",
                   "not a readable rosbag2 sqlite3 file: " + doing + ": " +
                       (db ? sqlite3_errmsg(db) : "cannot open"));
}

Database Open(const std::string& path) {
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  Database out(db);
  if (rc != SQLITE_OK) Fail(path, db, "opening it");
  return out;
}

Statement Prepare(const std::string& path, sqlite3* db, const std::string& sql) {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) {
    Fail(path, db, "reading its tables (" + sql + ")");
  }
  return Statement(s);
}

std::string Column(sqlite3_stmt* s, int i) {
  const unsigned char* text = sqlite3_column_text(s, i);
  return text ? reinterpret_cast<const char*>(text) : "";
}

// Topic id -> topic, with counts and spans when `with_counts`.
std::map<int64_t, BagTopic> Topics(const std::string& path, sqlite3* db, bool with_counts) {
  std::map<int64_t, BagTopic> out;
  Statement s = Prepare(path, db, "SELECT id, name, type, serialization_format FROM topics");
  int rc;
  while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
    BagTopic t;
    t.name = Column(s.get(), 1), t.type = Column(s.get(), 2);
    t.serialization = Column(s.get(), 3);
    out[sqlite3_column_int64(s.get(), 0)] = t;
  }
  if (rc != SQLITE_DONE) Fail(path, db, "reading its topics");
  if (!with_counts) return out;
  Statement c = Prepare(path, db,
                        "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages "
                        "GROUP BY topic_id");
  while ((rc = sqlite3_step(c.get())) == SQLITE_ROW) {
    const auto it = out.find(sqlite3_column_int64(c.get(), 0));
    if (it == out.end()) continue;
    it->second.count = static_cast<long>(sqlite3_column_int64(c.get(), 1));
    it->second.first_ns = sqlite3_column_int64(c.get(), 2);
    it->second.last_ns = sqlite3_column_int64(c.get(), 3);
  }
  if (rc != SQLITE_DONE) Fail(path, db, "counting its messages");
  return out;
}

}  // namespace

bool IsSqliteFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char header[16] = {};
  in.read(header, 16);
  return in && std::memcmp(header, "SQLite format 3", 16) == 0;
}

std::vector<BagTopic> ListSqliteBag(const std::string& path) {
  const Database db = Open(path);
  std::vector<BagTopic> out;
  for (const auto& [id, topic] : Topics(path, db.get(), true)) out.push_back(topic);
  std::sort(out.begin(), out.end(),
            [](const BagTopic& a, const BagTopic& b) { return a.name < b.name; });
  return out;
}

void ReadSqliteBag(const std::string& path, const std::vector<std::string>& topics,
                   const BagMessageVisitor& visit) {
  const Database db = Open(path);
  std::map<int64_t, BagTopic> wanted;
  for (const auto& [id, topic] : Topics(path, db.get(), false)) {
    if (std::find(topics.begin(), topics.end(), topic.name) != topics.end()) wanted[id] = topic;
  }
  Statement s = Prepare(path, db.get(),
                        "SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id");
  int rc;
  while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
    const auto it = wanted.find(sqlite3_column_int64(s.get(), 0));
    if (it == wanted.end()) continue;
    const void* blob = sqlite3_column_blob(s.get(), 2);
    const int size = sqlite3_column_bytes(s.get(), 2);
    visit(it->second, sqlite3_column_int64(s.get(), 1), static_cast<const uint8_t*>(blob),
          static_cast<size_t>(std::max(size, 0)));
  }
  if (rc != SQLITE_DONE) Fail(path, db.get(), "reading its messages");
}

}  // namespace slipgraph
