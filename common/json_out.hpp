// How tools write --json: one nlohmann::ordered_json object (Debian nlohmann-json3-dev) dumped on one line, so every
// string is escaped fully; numbers rounded to the digits the tool's table shows (rounded(v, 4) dumps as 0.8765,
// not 0.87649999...), a non-finite number as null. Header-only: tools link nlohmann_json::nlohmann_json.
#pragma once

#include <cmath>

#include <nlohmann/json.hpp>

namespace gpilot {

using json = nlohmann::ordered_json;  // keys in the order written, as a reader expects them

inline json rounded(double v, int decimals) {
  if (!std::isfinite(v)) return nullptr;
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

}  // namespace gpilot
