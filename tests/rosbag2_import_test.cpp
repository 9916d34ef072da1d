// ROS 2 bags import to the same drive log as the same data's ROS 1 bag: the tiny bag of
// tests/tiny_recordings.h, its messages stored as rosbag2's sqlite3 file, as MCAP (uncompressed,
// zstd, lz4), as a bag directory split over two files with a metadata.yaml, and as a directory
// without one; every file of the written logs byte for byte. Also: the topic listing, a cut-short
// MCAP imported up to its end with a warning, and the errors a user meets (a ros1_bag mapping, a
// storage file compressed by rosbag2, a directory without storage).
#include "io/rosbag2_import.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/log_writer.h"
#include "io/rosbag_import.h"
#include "tests/import_test_util.h"
#include "tests/ros2_bag_writer.h"
#include "tests/tiny_recordings.h"

namespace slipgraph {
namespace {

namespace fs = std::filesystem;
using testing::StoredMessage;

std::string Temp(const std::string& name) { return ::testing::TempDir() + "/" + name; }

// The tiny bag's mapping with format ros_bag, in a file of the running test's own (ctest runs
// this file's tests side by side: one file written by several would be read half written).
std::string Ros2Mapping() {
  std::string text = testing::kBagMapping;
  text.replace(text.find("ros1_bag"), 8, "ros_bag");
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string prefix = test == nullptr ? "" : std::string(test->name()) + ".";
  return testing::WriteText(::testing::TempDir(), prefix + "ros_bag.yaml", text);
}

// The tiny ROS 1 bag's messages as a ROS 2 bag stores them.
std::vector<StoredMessage> TinyMessages(const std::string& ros1_bag) {
  std::vector<StoredMessage> out;
  ForEachRosBagMessage(ros1_bag, {"/imu", "/odom", "/fix"},
                       [&](const std::string& topic, double t, const RosMessage& m) {
                         out.push_back(testing::Store(topic, t, m));
                       });
  return out;
}

std::string FileText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Every file of the two drive-log directories is the same.
void ExpectSameLogFiles(const std::string& a, const std::string& b) {
  size_t files = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(a)) {
    ++files;
    EXPECT_EQ(FileText(e.path()), FileText(fs::path(b) / e.path().filename()))
        << e.path().filename() << " of " << b;
  }
  EXPECT_GE(files, 4u);  // imu, attitude, wheels, gps (and vehicle.yaml)
}

TEST(Rosbag2Import, EveryStorageImportsAsTheRos1Bag) {
  const std::string ros1 = testing::WriteTinyBag(::testing::TempDir(), "same.bag");
  ImportReport report;
  WriteDriveLog(ImportRosBag(ros1, Ros2Mapping(), testing::TinyVehicle(), &report),
                Temp("from_ros1"));
  const std::vector<StoredMessage> messages = TinyMessages(ros1);
  ASSERT_EQ(messages.size(), 125u);

  std::vector<std::string> bags;
  testing::WriteSqliteBag(Temp("same.db3"), messages);
  bags.push_back(Temp("same.db3"));
  for (const std::string compression : {"", "zstd", "lz4"}) {
    const std::string path = Temp("same_" + compression + ".mcap");
    testing::WriteMcap(path, messages, compression, 50);
    bags.push_back(path);
  }
  // A bag directory split over two files in time order, with rosbag2's metadata.yaml.
  const std::string split = Temp("split_bag");
  fs::remove_all(split);
  fs::create_directories(split);
  const size_t half = messages.size() / 2;
  testing::WriteSqliteBag(split + "/split_bag_0.db3", {messages.begin(), messages.begin() + half});
  testing::WriteSqliteBag(split + "/split_bag_1.db3", {messages.begin() + half, messages.end()});
  std::ofstream(split + "/metadata.yaml")
      << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
         "  relative_file_paths:\n    - split_bag_0.db3\n    - split_bag_1.db3\n";
  bags.push_back(split);
  // The same with an older rosbag2's metadata (version 3), its paths from the bag's parent.
  const std::string old = Temp("old_bag");
  fs::remove_all(old);
  fs::create_directories(old);
  fs::copy(split + "/split_bag_0.db3", old + "/old_bag_0.db3");
  fs::copy(split + "/split_bag_1.db3", old + "/old_bag_1.db3");
  std::ofstream(old + "/metadata.yaml")
      << "rosbag2_bagfile_information:\n  version: 3\n  storage_identifier: sqlite3\n"
         "  relative_file_paths:\n    - old_bag/old_bag_0.db3\n    - old_bag/old_bag_1.db3\n";
  bags.push_back(old);
  // A directory without metadata: its storage files by name.
  const std::string bare = Temp("bare_bag");
  fs::remove_all(bare);
  fs::create_directories(bare);
  testing::WriteMcap(bare + "/a.mcap", messages, "zstd");
  bags.push_back(bare);

  for (const std::string& bag : bags) {
    SCOPED_TRACE(bag);
    ASSERT_TRUE(IsRos2Bag(bag));
    EXPECT_FALSE(IsRosBag(bag));
    ImportReport ros2_report;
    const DriveLog log = ImportRos2Bag(bag, Ros2Mapping(), testing::TinyVehicle(), &ros2_report);
    const std::string out = Temp("from_" + fs::path(bag).filename().string());
    WriteDriveLog(log, out);
    ExpectSameLogFiles(Temp("from_ros1"), out);
    EXPECT_EQ(ros2_report.lines, report.lines);
    const std::vector<SourceEntry> topics = ListRos2Bag(bag);
    ASSERT_EQ(topics.size(), 3u);
    EXPECT_EQ(topics[1].name, "/imu");
    EXPECT_EQ(topics[1].type, "sensor_msgs/msg/Imu");
    EXPECT_EQ(topics[1].count, 100);
    EXPECT_NEAR(topics[1].rate_hz, 50.0, 1e-6);
  }
}

TEST(Rosbag2Import, SplitFilesWithoutMetadataComeInTheirNumbersOrder) {
  const std::string dir = Temp("numbered_bag");
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"bag_10.db3", "bag_2.db3", "bag_0.db3", "bag_1.db3"}) {
    testing::WriteSqliteBag(dir + "/" + name, {});
  }
  std::vector<std::string> names;
  for (const std::string& file : Ros2BagFiles(dir)) {
    names.push_back(fs::path(file).filename().string());
  }
  EXPECT_EQ(names, (std::vector<std::string>{"bag_0.db3", "bag_1.db3", "bag_2.db3", "bag_10.db3"}));
}

TEST(Rosbag2Import, ACutShortMcapImportsUpToItsEndAndSaysSo) {
  const std::string ros1 = testing::WriteTinyBag(::testing::TempDir(), "cut.bag");
  const std::string path = Temp("cut.mcap");
  testing::WriteMcap(path, TinyMessages(ros1), "lz4", 25, 60);
  ImportReport report;
  const DriveLog log = ImportRos2Bag(path, Ros2Mapping(), testing::TinyVehicle(), &report);
  EXPECT_FALSE(log.imu.empty());
  bool warned = false;
  for (const std::string& line : report.lines) {
    warned = warned || line.find("warning: ") == 0;
  }
  EXPECT_TRUE(warned);
}

TEST(Rosbag2Import, ErrorsAUserMeets) {
  const std::string ros1 = testing::WriteTinyBag(::testing::TempDir(), "errors.bag");
  const std::string bag = Temp("errors.db3");
  testing::WriteSqliteBag(bag, TinyMessages(ros1));
  ImportReport report;
  const std::string ros1_mapping =
      testing::WriteText(::testing::TempDir(), "ros1.yaml", testing::kBagMapping);
  std::string e =
      testing::ErrorOf([&] { ImportRos2Bag(bag, ros1_mapping, testing::TinyVehicle(), &report); });
  EXPECT_NE(e.find("format"), std::string::npos) << e;

  const std::string compressed = Temp("compressed_bag");
  fs::remove_all(compressed);
  fs::create_directories(compressed);
  std::ofstream(compressed + "/b_0.db3.zstd") << "zstd bytes";
  std::ofstream(compressed + "/metadata.yaml")
      << "rosbag2_bagfile_information:\n  relative_file_paths: [b_0.db3.zstd]\n";
  EXPECT_TRUE(IsRos2Bag(compressed));
  e = testing::ErrorOf([&] { ListRos2Bag(compressed); });
  EXPECT_NE(e.find("b_0.db3.zstd"), std::string::npos) << e;
  EXPECT_NE(e.find("decompress it first"), std::string::npos) << e;

  const std::string empty = Temp("empty_dir");
  fs::create_directories(empty);
  EXPECT_FALSE(IsRos2Bag(empty));
  e = testing::ErrorOf([&] { Ros2BagFiles(empty); });
  EXPECT_NE(e.find("no ROS 2 storage file"), std::string::npos) << e;

  // A topic mapped to a type the importer does not read.
  std::vector<StoredMessage> messages = TinyMessages(ros1);
  for (StoredMessage& m : messages) {
    if (m.topic == "/fix") m.type = "sensor_msgs/msg/Image";
  }
  testing::WriteMcap(Temp("image.mcap"), messages, "");
  e = testing::ErrorOf(
      [&] { ImportRos2Bag(Temp("image.mcap"), Ros2Mapping(), testing::TinyVehicle(), &report); });
  EXPECT_NE(e.find("/fix"), std::string::npos) << e;
  EXPECT_NE(e.find("sensor_msgs/msg/Image"), std::string::npos) << e;
}

}  // namespace
}  // namespace slipgraph
