// Reading small JSON input files for the subcommands, with errors that name the field.
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "engine/core/error.h"

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

}  // namespace cablelab::app
