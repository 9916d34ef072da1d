// Fuzzes the YAML configs: the input as vehicle.yaml, and as a model file for the bundled
// sample's vehicle. Each must give a configuration or throw InputError.
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_util.h"
#include "io/input_error.h"
#include "io/yaml_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const slipgraph::Vehicle vehicle = [] {
    std::vector<std::string> warnings;
    return slipgraph::ReadVehicleYaml(std::string(SLIPGRAPH_SOURCE_DIR) + "/data/sample/vehicle.yaml",
                                      &warnings);
  }();
  const std::string path = slipgraph::fuzz::ScratchDirectory() + "/config.yaml";
  slipgraph::fuzz::WriteFile(path, data, size);
  try {
    std::vector<std::string> warnings;
    slipgraph::ReadVehicleYaml(path, &warnings);
  } catch (const slipgraph::InputError&) {
  }
  try {
    slipgraph::ReadModelYaml(path, vehicle);
  } catch (const slipgraph::InputError&) {
  }
  return 0;
}
