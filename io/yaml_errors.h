// yaml-cpp's errors as the readers' own. A file whose YAML parses but whose structure is not the
// one expected (a scalar where a mapping belongs, a list where a number does) makes yaml-cpp
// throw from inside a lookup or a conversion; the readers walk their files through
// NamingYamlErrors so that this reaches the user as an InputError naming the file and line.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "io/input_error.h"

namespace slipgraph {

template <typename Read>
auto NamingYamlErrors(const std::string& path, const Read& read) -> decltype(read()) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.is_null() ? 0 : e.mark.line + 1, "", "",
                     "not the structure expected here: " + e.msg);
  }
}

}  // namespace slipgraph
