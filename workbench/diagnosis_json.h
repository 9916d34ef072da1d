// A Diagnosis as the JSON object `diagnose --json` writes and the Python module returns.
#pragma once

#include <nlohmann/json.hpp>

#include "workbench/diagnosis.h"

namespace slipgraph {

nlohmann::json ToJson(const Diagnosis& diagnosis);
// The catalogue of physical effects (model/effect_catalogue.h) and the model terms the simulator
// does not have, each with whether diagnose tests it ("candidate"; a "model_parameter" only with
// --parameters) and whether `--with` can add it ("can_add"), as `slipgraph effects --json` writes
// it and the Python module returns it.
nlohmann::json EffectCatalogueJson();

}  // namespace slipgraph
