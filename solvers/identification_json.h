// An identification's result and a model's scores as the JSON objects `identify --json` writes
// and the Python module returns.
#pragma once

#include <nlohmann/json.hpp>

#include "solvers/model_identification.h"

namespace slipgraph {

nlohmann::json ToJson(const ModelScore& score);
nlohmann::json ToJson(const IdentificationResult& result);

}  // namespace slipgraph
