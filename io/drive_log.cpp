#include "io/drive_log.h"

#include <algorithm>

namespace slipgraph {

const char* SideName(Side side) { return side == Side::kLeft ? "left" : "right"; }

bool DriveLog::Has(const std::string& file_name) const {
  return std::find(present_files.begin(), present_files.end(), file_name) != present_files.end();
}

}  // namespace slipgraph
