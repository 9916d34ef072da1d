// Catalogue of the simulator's switchable physical effects. Each has a name (the one `diagnose`
// will report and `--effect NAME[=VALUE]` switches on), a default magnitude with its unit, the
// physics the simulator applies, and the evidence that betrays its absence from a model.
// None of them is in the estimators' default model: on a log simulated with one of them, that
// effect is "hidden".
#pragma once

#include <map>
#include <string>
#include <vector>

namespace slipgraph {
namespace sim {

struct EffectInfo {
  std::string name;
  double default_value;
  std::string unit;
  std::string physics;   // what the simulator does with it
  std::string evidence;  // what betrays its absence in a model's residuals
  // false for effects deliberately outside the estimators' candidate catalogue, used to test
  // that the workbench answers "no candidate explains it".
  bool in_model_catalogue;
};

const std::vector<EffectInfo>& EffectCatalogue();
// nullptr when `name` is not in the catalogue.
const EffectInfo* FindEffect(const std::string& name);

// Effects switched on, by name, with their magnitudes.
using EffectSet = std::map<std::string, double>;

// Parses "NAME" or "NAME=VALUE" into `effects`. False with a message for an unknown name or a
// bad value.
bool ParseEffect(const std::string& text, EffectSet* effects, std::string* error);

// The magnitude of `name` when on, else 0.
inline double EffectValue(const EffectSet& effects, const std::string& name) {
  const auto it = effects.find(name);
  return it == effects.end() ? 0.0 : it->second;
}

}  // namespace sim
}  // namespace slipgraph
