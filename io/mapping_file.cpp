#include "io/mapping_file.h"

#include <algorithm>

#include "io/input_error.h"

namespace slipgraph {

void CheckMappingKeys(const YAML::Node& node, const std::string& section,
                      const std::vector<std::string>& known, const std::string& path) {
  if (!node.IsMap()) throw InputError(path, 0, section, "", "expected a map");
  for (const auto& item : node) {
    const std::string key = item.first.as<std::string>();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      throw InputError(path, item.first.Mark().line + 1,
                       section.empty() ? key : section + "." + key, "", "unknown key");
    }
  }
}

}  // namespace slipgraph
