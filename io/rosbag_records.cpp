#include "io/rosbag_records.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "io/input_error.h"

namespace slipgraph {
namespace {

constexpr char kVersionLine[] = "#ROSBAG V2.0\n";

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
    WalkRecords(version_size, size_, "in the file");
  }

 private:
  // The records from `begin` to `end` of the file; `where` says in what, for errors.
  void WalkRecords(uint64_t begin, uint64_t end, const std::string& where) {
    uint64_t at = begin;
    while (at < end) {
      const uint64_t header_size = Length(at, end, where, "header length");
      const std::string header = Read(at + 4, header_size);
      const uint64_t data_at = at + 4 + header_size + 4;
      const uint64_t data_size = Length(at + 4 + header_size, end, where, "data length");
      const std::string compression = CheckFields(header, at);
      if (Field(header, "op") == std::string(1, '\x05') && compression == "none") {
        WalkRecords(data_at, data_at + data_size, "in the chunk at byte " + std::to_string(at));
      }
      at = data_at + data_size;
    }
  }

  // A 4-byte length at `at` and the bytes it claims after it, within `end`.
  uint64_t Length(uint64_t at, uint64_t end, const std::string& where, const std::string& what) {
    if (at + 4 > end) Fail(at, where, what + " beyond its end");
    const std::string bytes = Read(at, 4);
    uint32_t length = 0;
    for (int i = 3; i >= 0; --i) length = (length << 8) | static_cast<uint8_t>(bytes[i]);
    if (at + 4 + length > end) {
      Fail(at, where,
           what + " " + std::to_string(length) + " reaches beyond its end (" +
               std::to_string(end - at - 4) + " bytes left)");
    }
    return length;
  }

  // Checks that the header's fields fit in it; returns its compression field ("" when none).
  std::string CheckFields(const std::string& header, uint64_t record_at) {
    size_t at = 0;
    while (at < header.size()) {
      if (at + 4 > header.size()) Fail(record_at, "in its header", "a field length beyond its end");
      uint32_t length = 0;
      for (int i = 3; i >= 0; --i) length = (length << 8) | static_cast<uint8_t>(header[at + i]);
      if (at + 4 + length > header.size()) {
        Fail(record_at, "in its header", "a field of " + std::to_string(length) + " bytes");
      }
      if (header.substr(at + 4, length).find('=') == std::string::npos) {
        Fail(record_at, "in its header", "a field without '='");
      }
      at += 4 + length;
    }
    return Field(header, "compression");
  }

  // The value of the header field `name`, "" when it has none (the fields fit: CheckFields).
  static std::string Field(const std::string& header, const std::string& name) {
    size_t at = 0;
    while (at + 4 <= header.size()) {
      uint32_t length = 0;
      for (int i = 3; i >= 0; --i) length = (length << 8) | static_cast<uint8_t>(header[at + i]);
      const std::string field = header.substr(at + 4, length);
      if (field.compare(0, name.size() + 1, name + "=") == 0) return field.substr(name.size() + 1);
      at += 4 + length;
    }
    return "";
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
