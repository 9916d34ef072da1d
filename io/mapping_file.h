// What the importers' mapping files (YAML, loaded by LoadYamlFile of io/yaml_errors.h) share: the
// strict key check (a key the importer does not know is an error naming it: a typo must
// not fall back to a default silently) and the sd values' check. Used by matlab_import and
// rosbag_import.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace slipgraph {

// Throws InputError when `node` is not a map or has a key outside `known`; `section` ("" at the
// top) prefixes the key in the message ("imu.frame").
void CheckMappingKeys(const YAML::Node& node, const std::string& section,
                      const std::vector<std::string>& known, const std::string& path);

// A standard deviation the mapping states for a stream (`section`.`key`, e.g. gps.sd_v), or
// kMissing when it states none. Throws InputError naming the file, line and key when it is not a
// positive number (the log's reader would refuse it in the imported file).
double MappingSd(const YAML::Node& node, const std::string& section, const std::string& key,
                 const std::string& path);

}  // namespace slipgraph
