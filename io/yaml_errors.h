// yaml-cpp's errors as the readers' own, and the one YAML loader of the readers (vehicle.yaml,
// model files, the importers' mappings). A file whose YAML parses but whose structure is not the
// one expected (a scalar where a mapping belongs, a list where a number does) makes yaml-cpp
// throw from inside a lookup or a conversion; the readers walk their files through
// NamingYamlErrors so that this reaches the user as an InputError naming the file and line.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>

#include "io/input_error.h"
#include "io/text_file.h"

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

// Throws InputError naming the file, line and key where a mapping of `node`, or of anything under
// it, repeats a key: yaml-cpp keeps both and a lookup silently takes the first.
inline void RejectDuplicateKeys(const YAML::Node& node, const std::string& path,
                                const std::string& prefix = "") {
  if (node.IsMap()) {
    std::set<std::string> seen;
    for (const auto& entry : node) {
      const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
      if (!key.empty() && !seen.insert(key).second) {
        const YAML::Mark mark = entry.first.Mark();
        throw InputError(path, mark.is_null() ? 0 : mark.line + 1, prefix + key, "",
                         "duplicate key (a lookup would silently take the first)");
      }
      RejectDuplicateKeys(entry.second, path, prefix + key + ".");
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) RejectDuplicateKeys(item, path, prefix);
  }
}

// Parses `text`, the YAML document named `name` (its path, or what stands for it in errors).
// Throws InputError naming it and the line on a syntax error or a repeated key.
inline YAML::Node LoadYaml(const std::string& name, const std::string& text) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(name, e.mark.is_null() ? 0 : e.mark.line + 1, "", "",
                     "YAML syntax error: " + e.msg);
  }
  RejectDuplicateKeys(root, name);
  return root;
}

// The YAML file at `path`; InputError naming it when it cannot be read or parsed.
inline YAML::Node LoadYamlFile(const std::string& path) {
  return LoadYaml(path, ReadTextFile(path));
}

}  // namespace slipgraph
