#include "io/mapping_file.h"

#include <algorithm>
#include <cmath>

#include "io/drive_log.h"
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

double MappingSd(const YAML::Node& node, const std::string& section, const std::string& key,
                 const std::string& path) {
  const YAML::Node value = node[key];
  if (!value) return kMissing;
  const int line = value.Mark().line + 1;
  const std::string name = section + "." + key;
  double sd = 0.0;
  try {
    sd = value.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(path, line, name, value.IsScalar() ? value.Scalar() : "", "expected a number");
  }
  if (!(std::isfinite(sd) && sd > 0.0)) {
    throw InputError(path, line, name, value.Scalar(), "a standard deviation must be positive");
  }
  return sd;
}

}  // namespace slipgraph
