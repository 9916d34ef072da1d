// Whole-file text output with its errors checked: a report, a JSON document, a model file.
#pragma once

#include <string>

namespace slipgraph {

// Writes `text` to `path`, replacing the file. Throws InputError naming the path when it cannot
// be opened, written or closed (a missing directory, a full disk).
void WriteTextFile(const std::string& path, const std::string& text);

}  // namespace slipgraph
