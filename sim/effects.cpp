#include "sim/effects.h"

#include <cmath>
#include <cstdlib>

namespace slipgraph {
namespace sim {

bool ParseEffect(const std::string& text, EffectSet* effects, std::string* error) {
  const size_t equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const EffectInfo* effect = FindEffect(name);
  if (effect == nullptr) {
    *error = "unknown effect '" + name + "' (known:";
    for (const EffectInfo& known : EffectCatalogue()) *error += " " + known.name;
    *error += ")";
    return false;
  }
  double value = effect->default_value;
  if (equals != std::string::npos) {
    const std::string number = text.substr(equals + 1);
    char* end = nullptr;
    value = std::strtod(number.c_str(), &end);
    if (number.empty() || *end != '\0' || !std::isfinite(value)) {
      *error = "effect '" + name + "': value '" + number + "' is not a number";
      return false;
    }
  }
  (*effects)[name] = value;
  return true;
}

}  // namespace sim
}  // namespace slipgraph
