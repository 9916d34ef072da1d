// What the importers' mapping files (YAML) share: loading with an error naming the file and line,
// and the strict key check (a key the importer does not know is an error naming it: a typo must
// not fall back to a default silently). Used by matlab_import and rosbag_import.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace slipgraph {

// Throws InputError naming the file and line when it cannot be read or parsed.
YAML::Node LoadMappingFile(const std::string& path);

// Throws InputError when `node` is not a map or has a key outside `known`; `section` ("" at the
// top) prefixes the key in the message ("imu.frame").
void CheckMappingKeys(const YAML::Node& node, const std::string& section,
                      const std::vector<std::string>& known, const std::string& path);

}  // namespace slipgraph
