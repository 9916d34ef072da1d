#include "io/mcap_file.h"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>

#include "io/input_error.h"

namespace slipgraph {
namespace {

constexpr uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr uint8_t kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06, kFooter = 0x02,
                  kDataEnd = 0x0F;
// A chunk that claims to decompress to more than this (64 MiB) is taken as corrupt (writers make
// chunks of about 1 MB; rosbag2's default is 768 kB).
constexpr uint64_t kMaxChunkBytes = uint64_t{1} << 26;

// A record's content, read field by field; `offset` is its place in the file, for errors.
class Fields {
 public:
  Fields(const std::string& path, uint64_t offset, const uint8_t* data, size_t size)
      : path_(path), offset_(offset), data_(data), size_(size) {}

  uint16_t U16() { return static_cast<uint16_t>(Unsigned(2)); }
  uint32_t U32() { return static_cast<uint32_t>(Unsigned(4)); }
  uint64_t U64() { return Unsigned(8); }
  std::string String() {
    const uint32_t n = U32();
    const uint8_t* bytes = Take(n);
    return std::string(reinterpret_cast<const char*>(bytes), n);
  }
  // A uint32- or uint64-prefixed byte array.
  std::pair<const uint8_t*, size_t> Bytes(int length_bytes) {
    const uint64_t n = Unsigned(length_bytes);
    return {Take(n), static_cast<size_t>(n)};
  }
  std::pair<const uint8_t*, size_t> Rest() {
    const size_t n = size_ - at_;
    return {Take(n), n};
  }

 private:
  uint64_t Unsigned(int bytes) {
    const uint8_t* p = Take(bytes);
    uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
    return v;
  }
  const uint8_t* Take(uint64_t n) {
    if (n > size_ - at_) {
      throw InputError(path_, 0, "", "byte " + std::to_string(offset_),
                       "MCAP record shorter than its fields claim");
    }
    const uint8_t* p = data_ + at_;
    at_ += n;
    return p;
  }

  const std::string& path_;
  uint64_t offset_;
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

std::vector<uint8_t> Decompress(const std::string& path, uint64_t offset,
                                const std::string& compression, const uint8_t* in, size_t n,
                                uint64_t size) {
  const auto fail = [&](const std::string& why) {
    throw InputError(path, 0, "", "byte " + std::to_string(offset),
                     "MCAP chunk (" + (compression.empty() ? "uncompressed" : compression) +
                         ") does not decompress: " + why);
  };
  if (size > kMaxChunkBytes) fail("it claims " + std::to_string(size) + " bytes");
  if (compression.empty()) {
    if (size != n) fail("its size is not its records'");
    return std::vector<uint8_t>(in, in + n);
  }
  if (compression == "zstd" && ZSTD_getFrameContentSize(in, n) != size) {
    fail("its frame does not state the chunk's size");
  }
  if (compression == "lz4" && size / 255 > n) fail("it claims more than lz4 can expand to");
  std::vector<uint8_t> out(size);
  if (compression == "zstd") {
    const size_t got = ZSTD_decompress(out.data(), out.size(), in, n);
    if (ZSTD_isError(got)) fail(ZSTD_getErrorName(got));
    if (got != size)
      fail("it holds " + std::to_string(got) + " bytes, not " + std::to_string(size));
    return out;
  }
  if (compression == "lz4") {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) fail("no lz4 context");
    const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
        raw, LZ4F_freeDecompressionContext);
    size_t in_at = 0, out_at = 0, hint = 1;
    while (hint != 0 && in_at < n) {
      size_t out_n = out.size() - out_at, in_n = n - in_at;
      hint = LZ4F_decompress(ctx.get(), out.data() + out_at, &out_n, in + in_at, &in_n, nullptr);
      if (LZ4F_isError(hint)) fail(LZ4F_getErrorName(hint));
      if (in_n == 0 && out_n == 0) break;
      in_at += in_n, out_at += out_n;
    }
    if (hint != 0 || out_at != size) fail("the frame is incomplete or of another size");
    return out;
  }
  fail("compression '" + compression + "' is not read (zstd, lz4 or none)");
  return out;
}

struct Scan {
  std::map<uint16_t, std::string> schema_names;
  std::map<uint16_t, BagTopic> channels;
  const std::vector<std::string>* topics = nullptr;  // null: count every channel's messages
  const BagMessageVisitor* visit = nullptr;
};

// The records in [data, data + n), at `offset` in the file (inside a chunk: the chunk's).
// Returns false at the end of the data section.
bool ReadRecords(const std::string& path, uint64_t offset, const uint8_t* data, size_t n,
                 bool in_chunk, Scan* scan) {
  size_t at = 0;
  while (at < n) {
    const uint64_t record_offset = in_chunk ? offset : offset + at;
    if (n - at < 9) {
      throw InputError(path, 0, "", "byte " + std::to_string(record_offset),
                       "MCAP chunk ends inside a record header");
    }
    const uint8_t op = data[at];
    uint64_t length = 0;
    for (int i = 8; i >= 1; --i) length = (length << 8) | data[at + i];
    at += 9;
    if (length > n - at) {
      throw InputError(path, 0, "", "byte " + std::to_string(record_offset),
                       "MCAP record longer than its " + std::string(in_chunk ? "chunk" : "file"));
    }
    Fields f(path, record_offset, data + at, static_cast<size_t>(length));
    at += length;
    if (op == kSchema) {
      const uint16_t id = f.U16();
      scan->schema_names[id] = f.String();
    } else if (op == kChannel) {
      const uint16_t id = f.U16(), schema = f.U16();
      BagTopic topic;
      topic.name = f.String();
      topic.serialization = f.String();
      const auto it = scan->schema_names.find(schema);
      topic.type = it == scan->schema_names.end() ? "" : it->second;
      const auto old = scan->channels.find(id);
      if (old == scan->channels.end()) scan->channels[id] = topic;
    } else if (op == kMessage) {
      const uint16_t channel = f.U16();
      f.U32();  // sequence
      const int64_t log_time = static_cast<int64_t>(f.U64());
      f.U64();  // publish time
      const auto it = scan->channels.find(channel);
      if (it == scan->channels.end()) {
        throw InputError(path, 0, "", "byte " + std::to_string(record_offset),
                         "MCAP message on channel " + std::to_string(channel) +
                             ", which no Channel record before it defines");
      }
      BagTopic& topic = it->second;
      if (scan->visit == nullptr) {
        if (topic.count == 0 || log_time < topic.first_ns) topic.first_ns = log_time;
        topic.last_ns = std::max(topic.last_ns, log_time);
        ++topic.count;
      } else if (std::find(scan->topics->begin(), scan->topics->end(), topic.name) !=
                 scan->topics->end()) {
        const auto [bytes, size] = f.Rest();
        (*scan->visit)(topic, log_time, bytes, size);
      }
    } else if (op == kChunk && !in_chunk) {
      f.U64(), f.U64();  // message start and end time
      const uint64_t size = f.U64();
      f.U32();  // CRC of the uncompressed records (not checked)
      const std::string compression = f.String();
      const auto [records, records_n] = f.Bytes(8);
      const std::vector<uint8_t> plain =
          Decompress(path, record_offset, compression, records, records_n, size);
      ReadRecords(path, record_offset, plain.data(), plain.size(), true, scan);
    } else if (op == kDataEnd || op == kFooter) {
      return false;
    }
  }
  return true;
}

void ScanFile(const std::string& path, Scan* scan, std::string* cut_short) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path, 0, "", "", "cannot open");
  const uint64_t file_size = static_cast<uint64_t>(in.tellg());
  in.seekg(0);
  uint8_t magic[8] = {};
  in.read(reinterpret_cast<char*>(magic), 8);
  if (!in || std::memcmp(magic, kMagic, 8) != 0) {
    throw InputError(path, 0, "", "", "not an MCAP file (no magic at its start)");
  }
  if (cut_short) cut_short->clear();
  uint64_t at = 8;
  std::vector<uint8_t> record;
  while (at < file_size) {
    uint8_t header[9];
    if (file_size - at == 8) {  // the closing magic, or a record cut 8 bytes in
      uint8_t tail[8];
      in.read(reinterpret_cast<char*>(tail), 8);
      if (in && std::memcmp(tail, kMagic, 8) == 0) break;
      if (cut_short) {
        *cut_short = "the file ends inside a record at byte " + std::to_string(at) +
                     " (its header): read up to it";
      }
      return;
    }
    const auto stop = [&](const std::string& why) {
      if (cut_short)
        *cut_short = "the file ends inside a record at byte " + std::to_string(at) + " (" + why +
                     "): read up to it";
    };
    if (file_size - at < 9) {
      stop("its header");
      return;
    }
    in.read(reinterpret_cast<char*>(header), 9);
    uint64_t length = 0;
    for (int i = 8; i >= 1; --i) length = (length << 8) | header[i];
    if (length > file_size - at - 9) {
      stop("its content");
      return;
    }
    record.resize(9 + length);
    std::memcpy(record.data(), header, 9);
    in.read(reinterpret_cast<char*>(record.data() + 9), static_cast<std::streamsize>(length));
    if (!in) throw InputError(path, 0, "", "byte " + std::to_string(at), "read error");
    if (!ReadRecords(path, at, record.data(), record.size(), false, scan)) return;
    at += 9 + length;
  }
}

}  // namespace

bool IsMcapFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint8_t magic[8] = {};
  in.read(reinterpret_cast<char*>(magic), 8);
  return in && std::memcmp(magic, kMagic, 8) == 0;
}

std::vector<BagTopic> ListMcap(const std::string& path, std::string* cut_short) {
  Scan scan;
  ScanFile(path, &scan, cut_short);
  std::map<std::string, BagTopic> by_name;  // channels of one topic counted together
  for (const auto& [id, topic] : scan.channels) {
    BagTopic& t = by_name[topic.name];
    if (t.count == 0 || (topic.count > 0 && topic.first_ns < t.first_ns)) {
      t.first_ns = topic.first_ns;
    }
    t.last_ns = std::max(t.last_ns, topic.last_ns);
    t.name = topic.name, t.type = topic.type, t.serialization = topic.serialization;
    t.count += topic.count;
  }
  std::vector<BagTopic> out;
  for (const auto& [name, topic] : by_name) out.push_back(topic);
  return out;
}

void ReadMcap(const std::string& path, const std::vector<std::string>& topics,
              const BagMessageVisitor& visit, std::string* cut_short) {
  Scan scan;
  scan.topics = &topics;
  scan.visit = &visit;
  ScanFile(path, &scan, cut_short);
}

}  // namespace slipgraph
