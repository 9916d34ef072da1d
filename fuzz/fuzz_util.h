// What the fuzz targets share: a scratch directory of their own, files written whole, and the
// one kind of failure an input may cause (InputError, the readers' error naming file, line and
// field). Any other exception escapes to libFuzzer and is a finding, as a crash is.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/input_error.h"
#include "io/log_reader.h"
#include "io/log_writer.h"

namespace slipgraph {
namespace fuzz {

// A directory for this process (libFuzzer's -jobs run several).
inline const std::string& ScratchDirectory() {
  static const std::string dir = [] {
    const std::string d =
        (std::filesystem::temp_directory_path() / ("slipgraph_fuzz_" + std::to_string(getpid())))
            .string();
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

inline void WriteFile(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

inline void CopyFile(const std::string& from, const std::string& to) {
  std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing);
}

// An imported log must read back as the format requires (the importers' promise): written and
// read again, any InputError is a finding.
inline void CheckReadsBack(const DriveLog& log) {
  const std::string dir = ScratchDirectory() + "/imported";
  std::filesystem::remove_all(dir);
  try {
    WriteDriveLog(log, dir);
    ReadDriveLog(dir);
  } catch (const InputError& error) {
    std::fprintf(stderr, "imported log does not read back: %s\n", error.what());
    std::abort();
  }
}

}  // namespace fuzz
}  // namespace slipgraph
