#include "engine/statics/statics_io.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/core/error.h"

namespace cablelab {

namespace {

using nlohmann::json;

double readNumber(const json& value, const std::string& source, const std::string& field) {
  if (!value.is_number())
    throw InputError(source, field,
                     std::string("must be a number (got ") + value.type_name() + ")");
  const double v = value.get<double>();
  if (!std::isfinite(v))
    throw InputError(source, field, "must be finite (got " + value.dump() + ")");
  return v;
}

Vec2 readVec2(const json& value, const std::string& source, const std::string& field) {
  if (!value.is_array() || value.size() != 2)
    throw InputError(source, field,
                     "must be an array of 2 numbers [x, y] (got " +
                         (value.is_array() ? std::to_string(value.size()) + " entries"
                                           : std::string(value.type_name())) +
                         ")");
  return {readNumber(value[0], source, field + "[0]"), readNumber(value[1], source, field + "[1]")};
}

void rejectUnknownKeys(const json& object, std::initializer_list<const char*> known,
                       const std::string& source, const std::string& where) {
  for (const auto& item : object.items()) {
    bool ok = false;
    for (const char* k : known) ok |= item.key() == k;
    if (!ok)
      throw InputError(source, where.empty() ? item.key() : where + "." + item.key(),
                       "unknown key");
  }
}

}  // namespace

StaticsProblem parseStaticsJson(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double range
    throw InputError(source, "(json)", std::string("not valid JSON: ") + e.what());
  }
  if (!root.is_object()) throw InputError(source, "(root)", "must be a JSON object");
  rejectUnknownKeys(root, {"cables", "p0"}, source, "");
  if (!root.contains("cables")) throw InputError(source, "cables", "missing");
  const json& cables = root["cables"];
  if (!cables.is_array()) throw InputError(source, "cables", "must be an array");
  StaticsProblem problem;
  for (size_t i = 0; i < cables.size(); ++i) {
    const std::string at = "cables[" + std::to_string(i) + "]";
    const json& c = cables[i];
    if (!c.is_object()) throw InputError(source, at, "must be an object {a, b, k, L}");
    rejectUnknownKeys(c, {"a", "b", "k", "L"}, source, at);
    for (const char* key : {"a", "b", "k", "L"})
      if (!c.contains(key)) throw InputError(source, at + "." + key, "missing");
    StaticsCable cable;
    cable.a = readVec2(c["a"], source, at + ".a");
    cable.b = readVec2(c["b"], source, at + ".b");
    cable.k = readNumber(c["k"], source, at + ".k");
    cable.L = readNumber(c["L"], source, at + ".L");
    problem.cables.push_back(cable);
  }
  if (root.contains("p0")) problem.p0 = readVec2(root["p0"], source, "p0");
  validateStatics(problem, source);
  return problem;
}

StaticsProblem loadStaticsFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "(file)", "cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "(file)", "cannot read");
  return parseStaticsJson(text.str(), path);
}

std::string staticsResultToJson(const StaticsResult& result) {
  json out;
  out["p"] = {result.p.x(), result.p.y()};
  out["lengths"] = result.lengths;
  out["tensions"] = result.tensions;
  out["energy"] = result.energy;
  out["iterations"] = result.iterations;
  out["solve_us"] = result.solveMicros;
  out["residual"] = result.residual;
  out["solver"] = toString(result.method);
  out["converged"] = result.converged;
  if (result.anchor >= 0) out["fingertip"] = result.anchor;
  return out.dump();
}

}  // namespace cablelab
