// Reading small JSON input files for the subcommands, with errors that name the field.
#pragma once

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "engine/core/error.h"
#include "engine/core/math.h"

namespace cablelab::app {

inline nlohmann::json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "(file)", "cannot open the file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "(json)", std::string("not valid JSON: ") + e.what());
  }
}

inline double jsonNumber(const nlohmann::json& v, const std::string& file,
                         const std::string& field) {
  if (!v.is_number()) throw InputError(file, field, "must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw InputError(file, field, "must be finite");
  return d;
}

inline Vec2 jsonVec2(const nlohmann::json& v, const std::string& file, const std::string& field) {
  if (!v.is_array() || v.size() != 2) throw InputError(file, field, "must be [x, y]");
  return Vec2(jsonNumber(v[0], file, field + "[0]"), jsonNumber(v[1], file, field + "[1]"));
}

}  // namespace cablelab::app
