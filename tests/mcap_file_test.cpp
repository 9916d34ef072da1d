// The MCAP reader on files written here from the format's specification (tests/ros2_bag_writer.h):
// chunks uncompressed, zstd and lz4 give the same messages in order; the topics are listed with
// their types, counts and time spans; a file cut short is read up to its last whole record and
// says so; a chunk whose bytes do not decompress, a record longer than its chunk and a message on
// an undefined channel are errors naming the file and the byte.
#include "io/mcap_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "io/input_error.h"
#include "tests/import_test_util.h"
#include "tests/ros2_bag_writer.h"

namespace slipgraph {
namespace {

using testing::StoredMessage;

// 300 messages on two topics at 100 and 50 Hz from t = 10 s.
std::vector<StoredMessage> Messages() {
  std::vector<StoredMessage> out;
  for (int i = 0; i < 200; ++i) {
    RosImu imu;
    imu.stamp_s = 10.0 + 0.01 * i;
    imu.linear_acceleration = {0.01 * i, 0.0, 9.8};
    out.push_back(testing::Store("/imu", imu.stamp_s, imu));
    if (i % 2 == 0) {
      RosOdometry odom;
      odom.stamp_s = 10.0 + 0.01 * i;
      odom.linear = {0.005 * i, 0.0, 0.0};
      out.push_back(testing::Store("/odom", odom.stamp_s, odom));
    }
  }
  return out;
}

std::vector<StoredMessage> Read(const std::string& path, const std::vector<std::string>& topics,
                                std::string* cut_short = nullptr) {
  std::vector<StoredMessage> out;
  ReadMcap(
      path, topics,
      [&](const BagTopic& topic, int64_t time_ns, const uint8_t* data, size_t size) {
        out.push_back({topic.name, topic.type, time_ns, std::vector<uint8_t>(data, data + size)});
      },
      cut_short);
  return out;
}

TEST(McapFile, EveryCompressionGivesTheSameMessages) {
  const std::vector<StoredMessage> written = Messages();
  for (const std::string compression : {"", "zstd", "lz4"}) {
    const std::string path = ::testing::TempDir() + "/every_" + compression + ".mcap";
    testing::WriteMcap(path, written, compression, 37);
    ASSERT_TRUE(IsMcapFile(path));
    std::string cut_short = "not cleared";
    const std::vector<StoredMessage> read = Read(path, {"/imu", "/odom"}, &cut_short);
    EXPECT_EQ(cut_short, "");
    ASSERT_EQ(read.size(), written.size()) << compression;
    for (size_t i = 0; i < read.size(); ++i) {
      EXPECT_EQ(read[i].topic, written[i].topic);
      EXPECT_EQ(read[i].type, written[i].type);
      EXPECT_EQ(read[i].time_ns, written[i].time_ns);
      EXPECT_EQ(read[i].data, written[i].data);
    }
    EXPECT_EQ(Read(path, {"/odom"}).size(), 100u);
    const std::vector<BagTopic> topics = ListMcap(path);
    ASSERT_EQ(topics.size(), 2u);
    EXPECT_EQ(topics[0].name, "/imu");
    EXPECT_EQ(topics[0].type, "sensor_msgs/msg/Imu");
    EXPECT_EQ(topics[0].serialization, "cdr");
    EXPECT_EQ(topics[0].count, 200);
    EXPECT_EQ(topics[0].first_ns, 10000000000);
    EXPECT_EQ(topics[0].last_ns, 11990000000);
    EXPECT_EQ(topics[1].count, 100);
  }
}

TEST(McapFile, AFileCutShortIsReadUpToItsLastWholeRecord) {
  const std::vector<StoredMessage> written = Messages();
  const std::string path = ::testing::TempDir() + "/cut.mcap";
  // Chunks of 30 messages; cut inside the last chunk, whose 30 messages are lost with it.
  testing::WriteMcap(path, written, "zstd", 30, 100);
  std::string cut_short;
  const std::vector<StoredMessage> read = Read(path, {"/imu", "/odom"}, &cut_short);
  EXPECT_EQ(read.size(), 270u);
  EXPECT_NE(cut_short.find("ends inside a record"), std::string::npos) << cut_short;
}

TEST(McapFile, CorruptChunksAndRecordsAreErrorsNamingTheByte) {
  const std::vector<StoredMessage> written = Messages();
  const std::string path = ::testing::TempDir() + "/corrupt.mcap";
  testing::WriteMcap(path, written, "zstd", 1000);
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(-200, std::ios::end);  // inside the one chunk's compressed bytes
  f.write("garbage garbage garbage", 23);
  f.close();
  std::string e = testing::ErrorOf([&] { Read(path, {"/imu"}); });
  EXPECT_NE(e.find("corrupt.mcap"), std::string::npos) << e;
  EXPECT_NE(e.find("does not decompress"), std::string::npos) << e;
  EXPECT_NE(e.find("byte "), std::string::npos) << e;

  // A message whose channel no record defines.
  testing::McapBytes bytes;
  const uint8_t magic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  bytes.Raw(std::vector<uint8_t>(magic, magic + 8));
  testing::McapBytes message;
  message.U16(9), message.U32(0), message.U64(1), message.U64(1), message.U8(0);
  bytes.Record(0x05, message);
  const std::string orphan = ::testing::TempDir() + "/orphan.mcap";
  std::ofstream(orphan, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.out.data()),
             static_cast<std::streamsize>(bytes.out.size()));
  e = testing::ErrorOf([&] { Read(orphan, {"/imu"}); });
  EXPECT_NE(e.find("channel 9"), std::string::npos) << e;

  // A string inside a record that claims more bytes than the record has.
  testing::McapBytes bad;
  bad.Raw(std::vector<uint8_t>(magic, magic + 8));
  testing::McapBytes schema;
  schema.U16(1), schema.U32(1000000);
  bad.Record(0x03, schema);
  const std::string short_field = ::testing::TempDir() + "/short_field.mcap";
  std::ofstream(short_field, std::ios::binary)
      .write(reinterpret_cast<const char*>(bad.out.data()),
             static_cast<std::streamsize>(bad.out.size()));
  e = testing::ErrorOf([&] { ListMcap(short_field); });
  EXPECT_NE(e.find("shorter than its fields claim"), std::string::npos) << e;

  const std::string not_mcap = ::testing::TempDir() + "/not.mcap";
  std::ofstream(not_mcap) << "hello";
  EXPECT_FALSE(IsMcapFile(not_mcap));
  EXPECT_THROW(ListMcap(not_mcap), InputError);
}

}  // namespace
}  // namespace slipgraph
