#include "io/text_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/input_error.h"

namespace slipgraph {

std::string ReadTextFile(const std::string& path) {
  if (std::filesystem::is_directory(path)) {
    throw InputError(path, 0, "", "", "cannot open file (a directory)");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, 0, "", "", "cannot open file");
  std::ostringstream contents;
  contents << file.rdbuf();
  if (file.bad()) throw InputError(path, 0, "", "", "read failed");
  return contents.str();
}

void WriteTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw InputError(path, 0, "", "", "cannot open file for writing");
  out << text;
  out.flush();
  if (!out) throw InputError(path, 0, "", "", "write failed (a full disk, or not a file)");
  out.close();
  if (out.fail()) throw InputError(path, 0, "", "", "closing the file failed");
}

}  // namespace slipgraph
