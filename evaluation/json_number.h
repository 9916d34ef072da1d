// A JSON number, null when not finite: JSON has no NaN, and a figure that was not measured is
// null in every JSON output.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>

namespace slipgraph {

inline nlohmann::json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace slipgraph
