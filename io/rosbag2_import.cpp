#include "io/rosbag2_import.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "io/cdr_reader.h"
#include "io/input_error.h"
#include "io/mcap_file.h"
#include "io/ros2_messages.h"
#include "io/ros_log_builder.h"
#include "io/sqlite_bag.h"
#include "io/yaml_errors.h"

namespace slipgraph {
namespace {

namespace fs = std::filesystem;

bool IsStorageName(const fs::path& p) {
  return p.extension() == ".db3" || p.extension() == ".mcap";
}

std::vector<std::string> FilesFromMetadata(const fs::path& directory) {
  const std::string metadata = (directory / "metadata.yaml").string();
  return NamingYamlErrors(metadata, [&] {
    const YAML::Node root = LoadYamlFile(metadata);
    const YAML::Node files = root["rosbag2_bagfile_information"]["relative_file_paths"];
    if (!files || !files.IsSequence()) {
      throw InputError(metadata, 0, "rosbag2_bagfile_information.relative_file_paths", "",
                       "missing: which storage files make up the bag");
    }
    std::vector<std::string> out;
    for (const YAML::Node& f : files) {
      // rosbag2 before metadata version 4 wrote the paths from the bag's parent directory
      // ("bag/bag_0.db3"); later versions from the bag's own.
      const fs::path in_bag = directory / f.as<std::string>();
      const fs::path in_parent = directory.parent_path() / f.as<std::string>();
      std::error_code ec;
      out.push_back(
          (!fs::exists(in_bag, ec) && fs::exists(in_parent, ec) ? in_parent : in_bag).string());
    }
    return out;
  });
}

// Reads every message of `topics` from the storage file, whichever its kind; `notes` gets what the
// reader noticed (a file cut short).
void ReadStorage(const std::string& file, const std::vector<std::string>& topics,
                 const BagMessageVisitor& visit, std::vector<std::string>* notes) {
  if (IsSqliteFile(file)) {
    ReadSqliteBag(file, topics, visit);
    return;
  }
  std::string cut_short;
  ReadMcap(file, topics, visit, &cut_short);
  if (!cut_short.empty()) notes->push_back(file + ": " + cut_short);
}

std::vector<BagTopic> ListStorage(const std::string& file, std::vector<std::string>* notes) {
  if (IsSqliteFile(file)) return ListSqliteBag(file);
  std::string cut_short;
  std::vector<BagTopic> out = ListMcap(file, &cut_short);
  if (!cut_short.empty()) notes->push_back(file + ": " + cut_short);
  return out;
}

}  // namespace

bool IsRos2Bag(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    if (fs::exists(fs::path(path) / "metadata.yaml", ec)) return true;
    for (const fs::directory_entry& e : fs::directory_iterator(path, ec)) {
      if (IsStorageName(e.path())) return true;
    }
    return false;
  }
  return IsSqliteFile(path) || IsMcapFile(path);
}

std::vector<std::string> Ros2BagFiles(const std::string& path) {
  std::vector<std::string> files;
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    files.push_back(path);
  } else if (fs::exists(fs::path(path) / "metadata.yaml", ec)) {
    files = FilesFromMetadata(path);
  } else {
    for (const fs::directory_entry& e : fs::directory_iterator(path, ec)) {
      if (IsStorageName(e.path())) files.push_back(e.path().string());
    }
    // rosbag2 numbers split files bag_0, bag_1, ..., bag_10: in that order, not the names'.
    const auto split_index = [](const std::string& file) {
      const std::string stem = fs::path(file).stem().string();
      const size_t underscore = stem.find_last_of('_');
      const std::string digits = underscore == std::string::npos ? "" : stem.substr(underscore + 1);
      const bool numbered = !digits.empty() && digits.size() < 10 &&
                            digits.find_first_not_of("0123456789") == std::string::npos;
      return std::make_pair(numbered ? stem.substr(0, underscore) : stem,
                            numbered ? std::stol(digits) : -1L);
    };
    std::sort(files.begin(), files.end(), [&](const std::string& a, const std::string& b) {
      return std::make_pair(split_index(a), a) < std::make_pair(split_index(b), b);
    });
  }
  if (files.empty()) {
    throw InputError(path, 0, "", "", "no ROS 2 storage file (.db3 or .mcap) in the directory");
  }
  for (const std::string& f : files) {
    if (!fs::exists(f, ec)) throw InputError(f, 0, "", "", "storage file listed but not there");
    if (IsSqliteFile(f) || IsMcapFile(f)) continue;
    const bool compressed = fs::path(f).extension() == ".zstd";
    throw InputError(f, 0, "", "",
                     compressed ? "a storage file compressed by rosbag2: decompress it first "
                                  "(zstd -d, and the metadata.yaml's file names with it)"
                                : "neither a rosbag2 sqlite3 file nor an MCAP file");
  }
  return files;
}

std::vector<SourceEntry> ListRos2Bag(const std::string& path, std::vector<std::string>* notes) {
  std::map<std::string, BagTopic> topics;
  std::vector<std::string> unused;
  for (const std::string& file : Ros2BagFiles(path)) {
    for (const BagTopic& t : ListStorage(file, notes ? notes : &unused)) {
      BagTopic& sum = topics[t.name];
      if (t.count > 0 && (sum.count == 0 || t.first_ns < sum.first_ns)) sum.first_ns = t.first_ns;
      if (t.count > 0) sum.last_ns = std::max(sum.last_ns, t.last_ns);
      sum.type = t.type, sum.count += t.count;
    }
  }
  std::vector<SourceEntry> out;
  for (const auto& [name, t] : topics) {
    SourceEntry e{name, t.type, t.count, 0.0};
    const double span_s = 1e-9 * static_cast<double>(t.last_ns - t.first_ns);
    if (e.count > 1 && span_s > 0.0) e.rate_hz = (e.count - 1) / span_s;
    out.push_back(e);
  }
  return out;
}

DriveLog ImportRos2Bag(const std::string& path, const std::string& mapping_path,
                       const Vehicle& vehicle, ImportReport* report) {
  RosLogBuilder builder(ReadRosMapping(mapping_path, RosBagKind::kRos2, vehicle), vehicle, path);
  const std::vector<std::string> topics = builder.topics();
  std::vector<std::string> notes;
  for (const std::string& file : Ros2BagFiles(path)) {
    ReadStorage(
        file, topics,
        [&](const BagTopic& topic, int64_t time_ns, const uint8_t* data, size_t size) {
          if (topic.serialization != "cdr") {
            throw InputError(file, 0, topic.name, topic.serialization,
                             "messages serialized as '" + topic.serialization +
                                 "': only CDR (rosbag2's) is read");
          }
          std::optional<RosMessage> message;
          try {
            message = DecodeRos2Message(topic.type, data, size);
          } catch (const CdrError& e) {
            throw InputError(file, 0, topic.name,
                             RosTimeText(1e-9 * static_cast<double>(time_ns)) + " (receive)",
                             "message does not decode as " + topic.type + ": " + e.what());
          }
          if (!message) {
            throw InputError(file, 0, topic.name, topic.type,
                             std::string("not a message type the importer reads (") +
                                 kRosTypesRead + ", with /msg/ in ROS 2)");
          }
          builder.Add(topic.name, *message);
        },
        &notes);
  }
  DriveLog log = builder.Finish(report);
  for (const std::string& note : notes) report->lines.push_back("warning: " + note);
  return log;
}

}  // namespace slipgraph
