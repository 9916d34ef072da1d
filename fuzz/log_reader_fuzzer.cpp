// Fuzzes the drive-log reader: the first byte picks one file of a small valid log (the bundled
// sample's first rows) and its skip-bad mode, the rest replaces that file's content. The reader
// must return a log or throw InputError; with --skip-bad, what it returns holds only finite,
// time-ordered rows.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz/fuzz_util.h"
#include "io/input_error.h"
#include "io/log_reader.h"

namespace {

const char* const kFiles[] = {"imu.csv",      "wheels.csv", "gps.csv",    "attitude.csv",
                              "vehicle.yaml", "truth.csv",  "events.csv", "commands.csv"};

// The bundled sample cut to its first 60 rows, once.
const std::string& SmallLog() {
  static const std::string dir = [] {
    const std::string d = slipgraph::fuzz::ScratchDirectory() + "/log";
    std::filesystem::create_directories(d);
    for (const char* name : kFiles) {
      std::ifstream in(std::string(SLIPGRAPH_SOURCE_DIR) + "/data/sample/" + name);
      std::ofstream out(d + "/" + name + ".orig");
      std::string line;
      for (int i = 0; i < 60 && std::getline(in, line); ++i) out << line << '\n';
    }
    return d;
  }();
  return dir;
}

void CheckFinite(const slipgraph::DriveLog& log) {
  double last = -INFINITY;
  for (const slipgraph::ImuSample& s : log.imu) {
    if (!std::isfinite(s.t) || !std::isfinite(s.ax) || !std::isfinite(s.gz) || s.t <= last) {
      std::abort();
    }
    last = s.t;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string& dir = SmallLog();
  for (const char* name : kFiles) {
    slipgraph::fuzz::CopyFile(dir + "/" + name + ".orig", dir + "/" + name);
  }
  const size_t file = data[0] % (sizeof(kFiles) / sizeof(kFiles[0]));
  slipgraph::fuzz::WriteFile(dir + "/" + kFiles[file], data + 1, size - 1);
  slipgraph::ReadOptions options;
  options.skip_bad = (data[0] & 0x80) != 0;
  try {
    const slipgraph::DriveLog log = slipgraph::ReadDriveLog(dir, options);
    CheckFinite(log);
  } catch (const slipgraph::InputError&) {
  }
  return 0;
}
