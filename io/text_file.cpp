#include "io/text_file.h"

#include <fstream>

#include "io/input_error.h"

namespace slipgraph {

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
