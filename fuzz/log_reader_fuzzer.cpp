// Fuzzes the drive-log reader on files held in memory: the first byte picks one file of a small
// valid log (the bundled sample's first rows) and its skip-bad mode, the rest replaces that
// file's text. The reader must return a log or throw InputError; what it returns holds only
// finite, time-ordered rows.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>

#include "io/input_error.h"
#include "io/log_reader.h"
#include "io/text_file.h"

namespace {

const char* const kFiles[] = {"imu.csv",      "wheels.csv", "gps.csv",    "attitude.csv",
                              "vehicle.yaml", "truth.csv",  "events.csv", "commands.csv"};

// The bundled sample's files cut to their first 60 lines, read once.
const std::map<std::string, std::string>& SmallLog() {
  static const std::map<std::string, std::string> files = [] {
    std::map<std::string, std::string> f;
    for (const char* name : kFiles) {
      const std::string text =
          slipgraph::ReadTextFile(std::string(SLIPGRAPH_SOURCE_DIR) + "/data/sample/" + name);
      size_t end = 0;
      for (int line = 0; line < 60 && end != std::string::npos; ++line) {
        end = text.find('\n', end + 1);
      }
      f[name] = text.substr(0, end == std::string::npos ? text.size() : end + 1);
    }
    return f;
  }();
  return files;
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
  std::map<std::string, std::string> files = SmallLog();
  files[kFiles[data[0] % (sizeof(kFiles) / sizeof(kFiles[0]))]] =
      std::string(reinterpret_cast<const char*>(data + 1), size - 1);
  slipgraph::ReadOptions options;
  options.skip_bad = (data[0] & 0x80) != 0;
  try {
    CheckFinite(
        slipgraph::ReadDriveLog(slipgraph::LogFilesInMemory("fuzz", std::move(files)), options));
  } catch (const slipgraph::InputError&) {
  }
  return 0;
}
