// Whole-file text input and output with their errors checked: a log's CSV files, a YAML file, a
// report, a JSON document, a model file.
#pragma once

#include <string>

namespace slipgraph {

// The bytes of the file at `path`. Throws InputError naming the path when it cannot be opened or
// read (missing, a directory, no permission).
std::string ReadTextFile(const std::string& path);

// Writes `text` to `path`, replacing the file. Throws InputError naming the path when it cannot
// be opened, written or closed (a missing directory, a full disk).
void WriteTextFile(const std::string& path, const std::string& text);

}  // namespace slipgraph
