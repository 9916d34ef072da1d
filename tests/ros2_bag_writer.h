// Writing of ROS 2 bags for the importer's tests: messages of io/ros_messages.h serialized in CDR
// (little- or big-endian), stored as rosbag2's sqlite3 file or as MCAP (chunks uncompressed or
// compressed with zstd or lz4), written field by field from the formats' specifications
// (rosbag2's sqlite3 schema; mcap.dev/spec) and independent of the reader's code.
#pragma once

#include <lz4frame.h>
#include <sqlite3.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "io/ros_messages.h"

namespace slipgraph {
namespace testing {

class CdrWriter {
 public:
  explicit CdrWriter(bool little_endian = true) : little_(little_endian) {
    bytes_ = {0, static_cast<uint8_t>(little_endian ? 1 : 0), 0, 0};
  }
  void U8(uint8_t v) { bytes_.push_back(v); }
  void U16(uint16_t v) { Put(v); }
  void I32(int32_t v) { Put(v); }
  void U32(uint32_t v) { Put(v); }
  void F64(double v) { Put(v); }
  void String(const std::string& s) {
    U32(static_cast<uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
  }
  template <size_t N>
  void Doubles(const std::array<double, N>& v) {
    for (double x : v) F64(x);
  }
  void Header(double stamp_s, const std::string& frame) {
    const double sec = std::floor(stamp_s);
    I32(static_cast<int32_t>(sec));
    U32(static_cast<uint32_t>(std::llround((stamp_s - sec) * 1e9)));
    String(frame);
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  template <typename T>
  void Put(T v) {
    while ((bytes_.size() - 4) % sizeof(T) != 0) bytes_.push_back(0);
    uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (!little_) std::reverse(b, b + sizeof(T));  // the test machine is little-endian
    bytes_.insert(bytes_.end(), b, b + sizeof(T));
  }

  bool little_;
  std::vector<uint8_t> bytes_;
};

// The ROS 2 type of a message ("sensor_msgs/msg/Imu").
inline std::string Ros2Type(const RosMessage& m) {
  const char* types[] = {kRosImuType, kRosOdometryType, kRosNavSatFixType, kRosJointStateType,
                         kRosTfMessageType};
  const std::string t = types[m.index()];
  const size_t slash = t.find('/');
  return t.substr(0, slash) + "/msg" + t.substr(slash);
}

inline std::vector<uint8_t> EncodeRos2(const RosMessage& message, bool little_endian = true) {
  CdrWriter w(little_endian);
  std::visit(
      [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        const std::array<double, 9> zero9{};
        const std::array<double, 36> zero36{};
        if constexpr (std::is_same_v<M, RosImu>) {
          w.Header(m.stamp_s, m.frame_id);
          w.Doubles(m.orientation_xyzw), w.Doubles(m.orientation_covariance);
          w.Doubles(m.angular_velocity), w.Doubles(zero9);
          w.Doubles(m.linear_acceleration), w.Doubles(zero9);
        } else if constexpr (std::is_same_v<M, RosOdometry>) {
          w.Header(m.stamp_s, "odom");
          w.String("base_link");
          w.Doubles(std::array<double, 7>{0, 0, 0, 0, 0, 0, 1}), w.Doubles(zero36);
          w.Doubles(m.linear), w.Doubles(m.angular), w.Doubles(zero36);
        } else if constexpr (std::is_same_v<M, RosNavSatFix>) {
          w.Header(m.stamp_s, "gps");
          w.U8(static_cast<uint8_t>(static_cast<int8_t>(m.status)));
          w.U16(1);
          w.F64(m.latitude_deg), w.F64(m.longitude_deg), w.F64(m.altitude_m);
          w.Doubles(m.position_covariance);
          w.U8(static_cast<uint8_t>(m.position_covariance_type));
        } else if constexpr (std::is_same_v<M, RosJointState>) {
          w.Header(m.stamp_s, "");
          w.U32(static_cast<uint32_t>(m.name.size()));
          for (const std::string& n : m.name) w.String(n);
          for (const std::vector<double>* v : {&m.position, &m.velocity}) {
            w.U32(static_cast<uint32_t>(v->size()));
            for (double x : *v) w.F64(x);
          }
          w.U32(0);  // effort
        } else {
          w.U32(static_cast<uint32_t>(m.transforms.size()));
          for (const RosTransform& t : m.transforms) {
            w.Header(0.0, t.parent_frame);
            w.String(t.child_frame);
            w.Doubles(t.translation), w.Doubles(t.rotation_xyzw);
          }
        }
      },
      message);
  return w.bytes();
}

// A message as a bag stores it.
struct StoredMessage {
  std::string topic, type;
  int64_t time_ns = 0;
  std::vector<uint8_t> data;
};

inline StoredMessage Store(const std::string& topic, double time_s, const RosMessage& m) {
  return {topic, Ros2Type(m), static_cast<int64_t>(std::llround(time_s * 1e9)), EncodeRos2(m)};
}

// rosbag2's sqlite3 storage (the schema of rosbag2_storage_default_plugins, Humble).
inline void WriteSqliteBag(const std::string& path, const std::vector<StoredMessage>& messages) {
  std::remove(path.c_str());
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) throw std::runtime_error("cannot open " + path);
  const auto exec = [&](const std::string& sql) {
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) {
      throw std::runtime_error(sqlite3_errmsg(db));
    }
  };
  exec(
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
      "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
      "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);");
  std::map<std::string, int> ids;
  for (const StoredMessage& m : messages) {
    if (ids.count(m.topic)) continue;
    ids[m.topic] = static_cast<int>(ids.size()) + 1;
    exec("INSERT INTO topics VALUES(" + std::to_string(ids[m.topic]) + ", '" + m.topic + "', '" +
         m.type + "', 'cdr', '')");
  }
  sqlite3_stmt* insert = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1,
                     &insert, nullptr);
  exec("BEGIN");
  for (const StoredMessage& m : messages) {
    sqlite3_bind_int(insert, 1, ids[m.topic]);
    sqlite3_bind_int64(insert, 2, m.time_ns);
    sqlite3_bind_blob(insert, 3, m.data.data(), static_cast<int>(m.data.size()), SQLITE_STATIC);
    if (sqlite3_step(insert) != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db));
    sqlite3_reset(insert);
  }
  exec("COMMIT");
  sqlite3_finalize(insert);
  sqlite3_close(db);
}

// MCAP records, little-endian.
class McapBytes {
 public:
  void U8(uint8_t v) { out.push_back(v); }
  void U16(uint16_t v) { Le(v, 2); }
  void U32(uint32_t v) { Le(v, 4); }
  void U64(uint64_t v) { Le(v, 8); }
  void String(const std::string& s) {
    U32(static_cast<uint32_t>(s.size()));
    out.insert(out.end(), s.begin(), s.end());
  }
  void Raw(const std::vector<uint8_t>& b) { out.insert(out.end(), b.begin(), b.end()); }
  void Record(uint8_t op, const McapBytes& content) {
    U8(op), U64(content.out.size()), Raw(content.out);
  }
  std::vector<uint8_t> out;

 private:
  void Le(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
};

// An MCAP file as rosbag2 writes one: a Header, a Schema per type, a Channel per topic, the
// messages in chunks of `per_chunk` compressed with `compression` ("", "zstd" or "lz4"), Data End,
// an empty summary and the Footer. `cut_bytes` > 0 leaves that many bytes off the end.
inline void WriteMcap(const std::string& path, const std::vector<StoredMessage>& messages,
                      const std::string& compression, size_t per_chunk = 64, size_t cut_bytes = 0) {
  McapBytes file;
  const uint8_t magic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  file.Raw(std::vector<uint8_t>(magic, magic + 8));
  McapBytes header;
  header.String("ros2"), header.String("slipgraph tests");
  file.Record(0x01, header);
  std::map<std::string, uint16_t> schema_of, channel_of;
  for (const StoredMessage& m : messages) {
    if (!schema_of.count(m.type)) {
      schema_of[m.type] = static_cast<uint16_t>(schema_of.size() + 1);
      McapBytes schema;
      schema.U16(schema_of[m.type]), schema.String(m.type), schema.String("ros2msg");
      schema.String("# definition not needed by the reader");
      file.Record(0x03, schema);
    }
    if (!channel_of.count(m.topic)) {
      channel_of[m.topic] = static_cast<uint16_t>(channel_of.size() + 1);
      McapBytes channel;
      channel.U16(channel_of[m.topic]), channel.U16(schema_of[m.type]), channel.String(m.topic);
      channel.String("cdr"), channel.U32(0);  // no metadata
      file.Record(0x04, channel);
    }
  }
  for (size_t first = 0; first < messages.size(); first += per_chunk) {
    McapBytes records;
    const size_t end = std::min(messages.size(), first + per_chunk);
    for (size_t i = first; i < end; ++i) {
      McapBytes message;
      message.U16(channel_of[messages[i].topic]), message.U32(static_cast<uint32_t>(i));
      message.U64(static_cast<uint64_t>(messages[i].time_ns));
      message.U64(static_cast<uint64_t>(messages[i].time_ns));
      message.Raw(messages[i].data);
      records.Record(0x05, message);
    }
    std::vector<uint8_t> packed = records.out;
    if (compression == "zstd") {
      packed.resize(ZSTD_compressBound(records.out.size()));
      packed.resize(
          ZSTD_compress(packed.data(), packed.size(), records.out.data(), records.out.size(), 3));
    } else if (compression == "lz4") {
      packed.resize(LZ4F_compressFrameBound(records.out.size(), nullptr));
      packed.resize(LZ4F_compressFrame(packed.data(), packed.size(), records.out.data(),
                                       records.out.size(), nullptr));
    }
    McapBytes chunk;
    chunk.U64(static_cast<uint64_t>(messages[first].time_ns));
    chunk.U64(static_cast<uint64_t>(messages[end - 1].time_ns));
    chunk.U64(records.out.size()), chunk.U32(0), chunk.String(compression);
    chunk.U64(packed.size()), chunk.Raw(packed);
    file.Record(0x06, chunk);
  }
  McapBytes data_end;
  data_end.U32(0);
  file.Record(0x0F, data_end);
  McapBytes footer;
  footer.U64(0), footer.U64(0), footer.U32(0);
  file.Record(0x02, footer);
  file.Raw(std::vector<uint8_t>(magic, magic + 8));
  file.out.resize(file.out.size() - std::min(cut_bytes, file.out.size()));
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(file.out.data()),
             static_cast<std::streamsize>(file.out.size()));
}

}  // namespace testing
}  // namespace slipgraph
