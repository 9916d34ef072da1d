// The catalogue of named physical effects: the names `diagnose` reports, `--with EFFECT`
// switches on in a model and `simulate --effect NAME` switches on in a simulation; for each, a
// default magnitude with its unit, the physics, and the evidence that betrays its absence from a
// model. None of them is in the estimators' default model.
#pragma once

#include <string>
#include <vector>

namespace slipgraph {

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

}  // namespace slipgraph
