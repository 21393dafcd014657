// Pieces of the JSON reports the scripted scenarios print (ui/scenario_script.h,
// ui/lecture_scripts.h, ui/timeline_scenarios.h).
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cablelab::ui {

/// `s` as a JSON string, quotes and escapes included.
inline std::string jsonQuoted(const std::string& s) {
  return nlohmann::json(s).dump();
}

/// `v` to the last bit (17 significant digits); -1 for a value that is not finite, the reports'
/// "nothing measured".
inline std::string jsonNumber(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", std::isfinite(v) ? v : -1.0);
  return b;
}

/// `items`, each already JSON, as a JSON array.
inline std::string jsonList(const std::vector<std::string>& items) {
  std::string out = "[";
  for (size_t k = 0; k < items.size(); ++k) out += (k ? ", " : "") + items[k];
  return out + "]";
}

}  // namespace cablelab::ui
