// The simulator's switchable physical effects (catalogue: model/effect_catalogue.h). On a log
// simulated with one of them, that effect is "hidden" from the estimators' default model.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "model/effect_catalogue.h"

namespace slipgraph {
namespace sim {

// The catalogue lives in model/ (the estimators name effects too); the simulator uses it here.
using slipgraph::EffectCatalogue;
using slipgraph::EffectInfo;
using slipgraph::FindEffect;

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
