// What the fuzz targets share: a scratch directory of their own, files written whole, and the
// one kind of failure an input may cause (InputError, the readers' error naming file, line and
// field). Any other exception escapes to libFuzzer and is a finding, as a crash is.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace slipgraph {
namespace fuzz {

// A directory for this process (libFuzzer's -jobs run several).
inline const std::string& ScratchDirectory() {
  static const std::string dir = [] {
    const std::string d = (std::filesystem::temp_directory_path() /
                           ("slipgraph_fuzz_" + std::to_string(getpid())))
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

}  // namespace fuzz
}  // namespace slipgraph
