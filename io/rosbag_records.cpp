#include "io/rosbag_records.h"

#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "io/input_error.h"

namespace slipgraph {
namespace {

constexpr char kVersionLine[] = "#ROSBAG V2.0\n";

// Record kinds (the header's "op" field).
constexpr char kMessageData = 0x02, kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05,
               kChunkInfo = 0x06, kConnection = 0x07;

// Little-endian unsigned integer of `bytes` (at most 8).
uint64_t LittleEndian(const std::string& bytes, size_t at = 0, size_t size = 0) {
  if (size == 0) size = bytes.size() - at;
  uint64_t value = 0;
  for (size_t i = size; i-- > 0;) value = (value << 8) | static_cast<uint8_t>(bytes[at + i]);
  return value;
}

// The byte size of the header fields that hold numbers; "op" is one byte.
const std::map<std::string, size_t>& FieldSizes() {
  static const std::map<std::string, size_t> sizes = {
      {"op", 1},        {"index_pos", 8}, {"conn_count", 4}, {"chunk_count", 4},
      {"size", 4},      {"ver", 4},       {"conn", 4},       {"count", 4},
      {"chunk_pos", 8}, {"time", 8},      {"start_time", 8}, {"end_time", 8}};
  return sizes;
}

struct Record {
  uint64_t at = 0;  // the byte of its header length
  std::map<std::string, std::string> fields;
  uint64_t data_at = 0, data_size = 0;
  char op() const {
    const auto op = fields.find("op");
    return op == fields.end() ? 0 : op->second[0];
  }
};

struct Chunk {
  uint64_t size = 0;                 // uncompressed
  bool compressed = false;           // its records are the decompressor's to judge
  std::set<uint64_t> record_starts;  // within the uncompressed data, when not compressed
};

class RecordWalker {
 public:
  explicit RecordWalker(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw InputError(path, 0, "", "", "cannot open file");
    in_.seekg(0, std::ios::end);
    size_ = static_cast<uint64_t>(in_.tellg());
  }

  void Walk() {
    const size_t version_size = sizeof(kVersionLine) - 1;
    if (size_ < version_size || Read(0, version_size) != kVersionLine) {
      throw InputError(path_, 0, "", "", "not a ROS bag of format 2.0 (no '#ROSBAG V2.0' line)");
    }
    std::set<uint64_t> record_starts;
    std::map<uint64_t, Chunk> chunks;  // by position
    const Chunk* last_chunk = nullptr;
    std::vector<std::pair<uint64_t, uint64_t>> chunk_infos;  // (where, its chunk_pos)
    uint64_t index_pos = 0;
    bool has_header = false;
    for (uint64_t at = version_size; at < size_;) {
      const Record record = ReadRecord(at, size_, "in the file");
      record_starts.insert(at);
      switch (record.op()) {
        case kBagHeader:
          index_pos = Number(record, "index_pos");
          has_header = true;
          break;
        case kChunk:
          last_chunk = &(chunks[at] = ReadChunk(record));
          break;
        case kIndexData:
          CheckIndexData(record, last_chunk);
          break;
        case kChunkInfo:
          CheckCount(record, 8);
          chunk_infos.push_back({at, Number(record, "chunk_pos")});
          break;
        default:
          break;
      }
      at = record.data_at + record.data_size;
    }
    if (!has_header) Fail(version_size, "in the file", "no bag header record");
    // rosbag seeks to the index and to each chunk its chunk infos name.
    if (index_pos != size_ && record_starts.count(index_pos) == 0) {
      Fail(version_size, "the bag header",
           "index_pos " + std::to_string(index_pos) + " is not the start of a record");
    }
    for (const auto& [at, chunk_pos] : chunk_infos) {
      if (chunks.count(chunk_pos) == 0) {
        Fail(at, "a chunk info", "chunk_pos " + std::to_string(chunk_pos) + " is not a chunk");
      }
    }
  }

 private:
  // The record whose header length is at `at`, within `end`; its fields checked.
  Record ReadRecord(uint64_t at, uint64_t end, const std::string& where) {
    Record record;
    record.at = at;
    const uint64_t header_size = Length(at, end, where, "header length");
    const std::string header = Read(at + 4, header_size);
    record.data_size = Length(at + 4 + header_size, end, where, "data length");
    record.data_at = at + 4 + header_size + 4;
    record.fields = Fields(header, at, "in its header");
    // A connection record's data is a header too (topic, type, md5sum, definition).
    if (record.op() == kConnection) {
      Fields(Read(record.data_at, record.data_size), at, "in its data");
    }
    if (record.fields.count("op") == 0) Fail(at, where, "a record without 'op'");
    return record;
  }

  // The "name=value" fields of `bytes`, each behind its 4-byte length, all within `bytes`; the
  // numeric fields of their size.
  std::map<std::string, std::string> Fields(const std::string& bytes, uint64_t at,
                                            const std::string& where) {
    std::map<std::string, std::string> fields;
    for (size_t f = 0; f < bytes.size();) {
      if (f + 4 > bytes.size()) Fail(at, where, "a field length beyond its end");
      const uint64_t length = LittleEndian(bytes, f, 4);
      if (f + 4 + length > bytes.size()) {
        Fail(at, where, "a field of " + std::to_string(length) + " bytes");
      }
      const std::string field = bytes.substr(f + 4, length);
      const size_t equals = field.find('=');
      if (equals == std::string::npos) Fail(at, where, "a field without '='");
      const std::string name = field.substr(0, equals), value = field.substr(equals + 1);
      const auto size = FieldSizes().find(name);
      if (size != FieldSizes().end() && value.size() != size->second) {
        Fail(at, where,
             "field '" + name + "' of " + std::to_string(value.size()) + " bytes, not " +
                 std::to_string(size->second));
      }
      fields[name] = value;
      f += 4 + length;
    }
    return fields;
  }

  Chunk ReadChunk(const Record& record) {
    Chunk chunk;
    chunk.size = Number(record, "size");
    const auto compression = record.fields.find("compression");
    chunk.compressed = compression == record.fields.end() || compression->second != "none";
    if (chunk.compressed) return chunk;
    if (chunk.size != record.data_size) {
      Fail(record.at, "an uncompressed chunk",
           "size " + std::to_string(chunk.size) + " where it holds " +
               std::to_string(record.data_size) + " bytes");
    }
    const std::string where = "in the chunk at byte " + std::to_string(record.at);
    const uint64_t end = record.data_at + record.data_size;
    for (uint64_t at = record.data_at; at < end;) {
      const Record inner = ReadRecord(at, end, where);
      if (inner.op() == kMessageData) chunk.record_starts.insert(at - record.data_at);
      at = inner.data_at + inner.data_size;
    }
    return chunk;
  }

  // An index of the chunk before it: (time, offset) per message, each offset a message's record.
  void CheckIndexData(const Record& record, const Chunk* chunk) {
    if (chunk == nullptr) Fail(record.at, "in the file", "an index before any chunk");
    const uint64_t count = CheckCount(record, 12);
    const std::string entries = Read(record.data_at, record.data_size);
    for (uint64_t i = 0; i < count; ++i) {
      const uint64_t offset = LittleEndian(entries, 12 * i + 8, 4);
      const bool fits =
          chunk->compressed ? offset < chunk->size : chunk->record_starts.count(offset) > 0;
      if (!fits) {
        Fail(record.at, "an index",
             "message offset " + std::to_string(offset) + " is not a message of its chunk");
      }
    }
  }

  // The record's "count" field, checked against its data of `entry_size` bytes an entry.
  uint64_t CheckCount(const Record& record, uint64_t entry_size) {
    const uint64_t count = Number(record, "count");
    if (count * entry_size != record.data_size) {
      Fail(record.at, "in its header",
           "count " + std::to_string(count) + " for " + std::to_string(record.data_size) +
               " bytes of entries");
    }
    return count;
  }

  uint64_t Number(const Record& record, const std::string& name) {
    const auto field = record.fields.find(name);
    if (field == record.fields.end()) Fail(record.at, "in its header", "no field '" + name + "'");
    return LittleEndian(field->second);
  }

  // A 4-byte length at `at` and the bytes it claims after it, within `end`.
  uint64_t Length(uint64_t at, uint64_t end, const std::string& where, const std::string& what) {
    if (at + 4 > end) Fail(at, where, what + " beyond its end");
    const uint64_t length = LittleEndian(Read(at, 4));
    if (at + 4 + length > end) {
      Fail(at, where,
           what + " " + std::to_string(length) + " reaches beyond its end (" +
               std::to_string(end - at - 4) + " bytes left)");
    }
    return length;
  }

  std::string Read(uint64_t at, uint64_t size) {
    std::string bytes(size, '\0');
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(bytes.data(), static_cast<std::streamsize>(size));
    if (!in_) throw InputError(path_, 0, "", "", "read failed at byte " + std::to_string(at));
    return bytes;
  }

  [[noreturn]] void Fail(uint64_t at, const std::string& where, const std::string& what) const {
    throw InputError(path_, 0, "", "",
                     "ROS bag record at byte " + std::to_string(at) + " (" + where + "): " + what +
                         ": the bag is cut short or corrupted ('rosbag reindex' may recover a "
                         "bag whose recording stopped)");
  }

  std::string path_;
  std::ifstream in_;
  uint64_t size_ = 0;
};

}  // namespace

void CheckRosBagRecords(const std::string& path) { RecordWalker(path).Walk(); }

}  // namespace slipgraph
