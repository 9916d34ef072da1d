// Writes the seeds of recording_fuzzer: the tiny MATLAB file, the tiny ROS bag, the same bag as
// MCAP (uncompressed, zstd, lz4) and each of its message types as CDR, each behind the byte that
// picks it. Usage: recording_seeds DIRECTORY
#include <cstdio>
#include <fstream>
#include <string>

#include "io/rosbag_import.h"
#include "io/text_file.h"
#include "tests/ros2_bag_writer.h"
#include "tests/tiny_recordings.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: recording_seeds DIRECTORY\n");
    return 2;
  }
  const std::string dir = argv[1];
  const std::string mat = slipgraph::testing::WriteTinyMat(dir, "tiny.mat");
  const std::string bag = slipgraph::testing::WriteTinyBag(dir, "tiny.bag");
  std::ofstream(dir + "/matlab", std::ios::binary) << '\x00' << slipgraph::ReadTextFile(mat);
  std::ofstream(dir + "/bag", std::ios::binary) << '\x01' << slipgraph::ReadTextFile(bag);
  std::vector<slipgraph::testing::StoredMessage> messages;
  slipgraph::ForEachRosBagMessage(
      bag, {"/imu", "/odom", "/fix"},
      [&](const std::string& topic, double t, const slipgraph::RosMessage& m) {
        messages.push_back(slipgraph::testing::Store(topic, t, m));
      });
  for (const std::string compression : {"", "zstd", "lz4"}) {
    const std::string mcap = dir + "/tiny.mcap";
    slipgraph::testing::WriteMcap(mcap, messages, compression, 40);
    std::ofstream(dir + "/mcap_" + compression, std::ios::binary)
        << '\x02' << slipgraph::ReadTextFile(mcap);
    std::remove(mcap.c_str());
  }
  // One message of each type: the type's index behind the byte that picks CDR.
  const slipgraph::RosMessage one_of_each[] = {
      slipgraph::RosImu{}, slipgraph::RosOdometry{}, slipgraph::RosNavSatFix{},
      slipgraph::RosJointState{1.0, {"left", "right"}, {0.1, 0.2}, {3.0, 4.0}},
      slipgraph::RosTfMessage{{{"base_link", "imu_link", {0, 0, 0}, {0, 0, 0, 1}}}}};
  for (int type = 0; type < 5; ++type) {
    const std::vector<uint8_t> bytes = slipgraph::testing::EncodeRos2(one_of_each[type]);
    std::ofstream out(dir + "/cdr_" + std::to_string(type), std::ios::binary);
    out << '\x03' << static_cast<char>(type);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  }
  std::remove(mat.c_str());
  std::remove(bag.c_str());
  return 0;
}
