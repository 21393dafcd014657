#include "engine/statics/statics_io.h"

#include <nlohmann/json.hpp>

#include "engine/core/file_input.h"
#include "engine/core/json_reader.h"

namespace cablelab {

using nlohmann::json;

StaticsProblem parseStaticsJson(const std::string& text, const std::string& source) {
  const json root = parseJsonText(text, source);
  StaticsProblem problem;
  {
    JsonReader r(root, source);
    r.onlyKeys({"cables", "p0"});
    const json& cables = r.requiredList("cables");
    for (size_t i = 0; i < cables.size(); ++i) {
      JsonReader c = r.item("cables", i);
      c.onlyKeys({"a", "b", "k", "L"});
      StaticsCable cable;
      cable.a = c.requiredVec2("a");
      cable.b = c.requiredVec2("b");
      cable.k = c.requiredNumber("k");
      cable.L = c.requiredNumber("L");
      problem.cables.push_back(cable);
    }
    if (r.has("p0")) problem.p0 = r.vec2("p0", Vec2::Zero());
  }
  validateStatics(problem, source);
  return problem;
}

StaticsProblem loadStaticsFile(const std::string& path) {
  return parseStaticsJson(readInputFile(path), path);
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
