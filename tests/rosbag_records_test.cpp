// The ROS bag record check that runs before the rosbag library: bags written by rosbag pass, and
// a length that claims more than its file, chunk or header holds is an error naming its byte.
#include "io/rosbag_records.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "io/input_error.h"
#include "io/text_file.h"
#include "tests/import_test_util.h"
#include "tests/tiny_recordings.h"

namespace slipgraph {
namespace {

using testing::ErrorOf;

std::string Le32(uint32_t n) {
  std::string bytes(4, '\0');
  for (int i = 0; i < 4; ++i) bytes[i] = static_cast<char>((n >> (8 * i)) & 0xff);
  return bytes;
}

std::string Le64(uint64_t n) { return Le32(n & 0xffffffffu) + Le32(n >> 32); }

std::string Field(const std::string& name, const std::string& value) {
  return Le32(static_cast<uint32_t>(name.size() + 1 + value.size())) + name + "=" + value;
}

std::string Record(const std::string& header, const std::string& data) {
  return Le32(static_cast<uint32_t>(header.size())) + header +
         Le32(static_cast<uint32_t>(data.size())) + data;
}

constexpr uint64_t kFirstRecord = 13;  // after "#ROSBAG V2.0\n"

std::string BagHeader(uint64_t index_pos) {
  return Record(Field("op", "\x03") + Field("index_pos", Le64(index_pos)) +
                    Field("conn_count", Le32(0)) + Field("chunk_count", Le32(1)),
                "");
}

// A bag header record, a chunk holding `chunk_data`, then `after` (its index, chunk infos); the
// header's index_pos is the end of the file, or `index_pos` when given.
std::string HandMadeBag(const std::string& compression, const std::string& chunk_data,
                        const std::string& after = "", uint64_t index_pos = 0) {
  const std::string chunk =
      Record(Field("op", "\x05") + Field("compression", compression) +
                 Field("size", Le32(static_cast<uint32_t>(chunk_data.size()))),
             chunk_data);
  const uint64_t end = kFirstRecord + BagHeader(0).size() + chunk.size() + after.size();
  return "#ROSBAG V2.0\n" + BagHeader(index_pos ? index_pos : end) + chunk + after;
}

uint64_t ChunkAt() { return kFirstRecord + BagHeader(0).size(); }

// The index of the chunk before it: one message at `offset` of the chunk's data.
std::string IndexData(uint32_t offset) {
  return Record(Field("op", "\x04") + Field("ver", Le32(1)) + Field("conn", Le32(0)) +
                    Field("count", Le32(1)),
                Le64(7) + Le32(offset));
}

std::string ChunkInfo(uint64_t chunk_pos) {
  return Record(Field("op", "\x06") + Field("ver", Le32(1)) + Field("chunk_pos", Le64(chunk_pos)) +
                    Field("start_time", Le64(0)) + Field("end_time", Le64(0)) +
                    Field("count", Le32(0)),
                "");
}

const std::string kMessage = Record(Field("op", "\x02") + Field("conn", Le32(0)), "abc");

std::string Write(const std::string& name, const std::string& bytes) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(RosBagRecords, ABagRosbagWrotePasses) {
  EXPECT_NO_THROW(CheckRosBagRecords(testing::WriteTinyBag(::testing::TempDir(), "records.bag")));
  EXPECT_NO_THROW(CheckRosBagRecords(Write("hand_made.bag", HandMadeBag("none", kMessage))));
  EXPECT_NO_THROW(CheckRosBagRecords(
      Write("indexed.bag", HandMadeBag("none", kMessage, IndexData(0) + ChunkInfo(ChunkAt())))));
}

// rosbag reads a message where the index says, and a chunk where a chunk info says: a corrupted
// offset read past its buffer (a segmentation fault in rosbag::Bag::readHeaderFromBuffer).
TEST(RosBagRecords, AnIndexThatPointsOffARecordIsAnError) {
  std::string e = ErrorOf([&] {
    CheckRosBagRecords(Write("bad_offset.bag", HandMadeBag("none", kMessage, IndexData(5))));
  });
  EXPECT_NE(e.find("message offset 5 is not a message of its chunk"), std::string::npos) << e;
  e = ErrorOf([&] {
    CheckRosBagRecords(Write("bad_chunk_pos.bag", HandMadeBag("none", kMessage, ChunkInfo(20))));
  });
  EXPECT_NE(e.find("chunk_pos 20 is not a chunk"), std::string::npos) << e;
  e = ErrorOf([&] {
    CheckRosBagRecords(Write("bad_index_pos.bag", HandMadeBag("none", kMessage, "", 14)));
  });
  EXPECT_NE(e.find("index_pos 14 is not the start of a record"), std::string::npos) << e;
}

// The fuzzer's finding: a length the library allocated as read (2.3 GB for a 71 kB file).
TEST(RosBagRecords, ALengthBeyondTheFileIsNamedWithItsByte) {
  std::string bytes = HandMadeBag("none", kMessage);
  bytes.replace(kFirstRecord, 4, Le32(0x8a000000u));
  const std::string e = ErrorOf([&] { CheckRosBagRecords(Write("long_header.bag", bytes)); });
  EXPECT_NE(e.find("long_header.bag"), std::string::npos) << e;
  EXPECT_NE(e.find("record at byte 13 (in the file): header length 2315255808"), std::string::npos)
      << e;
}

TEST(RosBagRecords, ABagCutShortIsNamed) {
  const std::string bag = ReadTextFile(testing::WriteTinyBag(::testing::TempDir(), "whole.bag"));
  const std::string e =
      ErrorOf([&] { CheckRosBagRecords(Write("cut.bag", bag.substr(0, bag.size() / 2))); });
  EXPECT_NE(e.find("cut short"), std::string::npos) << e;
}

TEST(RosBagRecords, AnUncompressedChunksRecordsAreChecked) {
  const std::string inner = Le32(1000) + kMessage.substr(4);
  const std::string e =
      ErrorOf([&] { CheckRosBagRecords(Write("bad_chunk.bag", HandMadeBag("none", inner))); });
  EXPECT_NE(e.find("in the chunk at byte"), std::string::npos) << e;
  EXPECT_NE(e.find("header length 1000"), std::string::npos) << e;
  // A compressed chunk's bytes are the decompressor's to judge.
  EXPECT_NO_THROW(CheckRosBagRecords(Write("bz2_chunk.bag", HandMadeBag("bz2", inner))));
}

// A connection record's data is parsed as a header: a field running past it read past rosbag's
// buffer (a heap overflow in ros::Header::parse).
TEST(RosBagRecords, AConnectionsDataIsCheckedAsAHeader) {
  const std::string fields = Field("topic", "/imu") + Field("type", "sensor_msgs/Imu");
  const auto connection = [&](const std::string& data) {
    return Record(Field("op", "\x07") + Field("conn", Le32(0)) + Field("topic", "/imu"), data);
  };
  EXPECT_NO_THROW(CheckRosBagRecords(
      Write("connection.bag", HandMadeBag("none", connection(fields) + kMessage))));
  const std::string e = ErrorOf([&] {
    CheckRosBagRecords(Write("bad_connection.bag",
                             HandMadeBag("none", connection(Le32(500) + fields) + kMessage)));
  });
  EXPECT_NE(e.find("in its data"), std::string::npos) << e;
}

TEST(RosBagRecords, AHeaderFieldBeyondItsHeaderAndNotABagAreErrors) {
  std::string bytes = HandMadeBag("none", kMessage);
  bytes.replace(kFirstRecord + 4, 4, Le32(200));  // the bag header's first field claims 200 bytes
  std::string e = ErrorOf([&] { CheckRosBagRecords(Write("long_field.bag", bytes)); });
  EXPECT_NE(e.find("in its header"), std::string::npos) << e;
  e = ErrorOf([&] { CheckRosBagRecords(Write("not_a.bag", "#ROSBAG V1.2\nold")); });
  EXPECT_NE(e.find("not a ROS bag of format 2.0"), std::string::npos) << e;
}

}  // namespace
}  // namespace slipgraph
