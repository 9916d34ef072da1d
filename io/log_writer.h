// Writes a DriveLog as a log directory (shared/log-format.md). Streams with no samples and not
// listed in present_files are not written (an absent file means an absent sensor).
#pragma once

#include <string>

#include "io/drive_log.h"

namespace slipgraph {

// Creates `directory` if needed. Throws InputError when a file cannot be written.
void WriteDriveLog(const DriveLog& log, const std::string& directory);

}  // namespace slipgraph
