// Fuzzes the YAML configs held in memory: the input as vehicle.yaml, and as a model file for the
// bundled sample's vehicle. Each must give a configuration or throw InputError.
#include <cstdint>
#include <string>
#include <vector>

#include "io/input_error.h"
#include "io/yaml_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const slipgraph::Vehicle vehicle = [] {
    std::vector<std::string> warnings;
    return slipgraph::ReadVehicleYaml(
        std::string(SLIPGRAPH_SOURCE_DIR) + "/data/sample/vehicle.yaml", &warnings);
  }();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::vector<std::string> warnings;
    slipgraph::ParseVehicleYaml("fuzz/vehicle.yaml", text, &warnings);
  } catch (const slipgraph::InputError&) {
  }
  try {
    slipgraph::ParseModelYaml("fuzz/model.yaml", text, vehicle);
  } catch (const slipgraph::InputError&) {
  }
  return 0;
}
