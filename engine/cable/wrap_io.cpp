#include "engine/cable/wrap_io.h"

#include <algorithm>
#include <cmath>

#include "engine/cable/wrap.h"
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/json_reader.h"

namespace cablelab {

using nlohmann::json;

namespace {

// Coordinates beyond this (m) would overflow squared lengths; like the statics input's bound.
constexpr double kMaxCoordinate = 1e9;

Vec2 bounded(const Vec2& v, const std::string& source, const std::string& field) {
  for (int i = 0; i < 2; ++i)
    if (std::abs(v[i]) > kMaxCoordinate)
      throw InputError(source, field + "[" + std::to_string(i) + "]",
                       "must be within +/-1e9 m" + gotValue(v[i]));
  return v;
}

}  // namespace

WrapProblem parseWrapJson(const json& in, const std::string& file) {
  WrapProblem p;
  std::string side;
  {
    JsonReader r(in, file);
    r.onlyKeys({"A", "B", "polygon", "side"});
    p.a = bounded(r.requiredVec2("A"), file, "A");
    p.b = bounded(r.requiredVec2("B"), file, "B");
    const json& polygon = r.requiredList("polygon");
    if (polygon.size() < 3)
      r.fail("polygon",
             "needs at least 3 vertices" + gotValue(static_cast<double>(polygon.size())));
    p.polygon = r.points("polygon");
    for (size_t i = 0; i < p.polygon.size(); ++i)
      bounded(p.polygon[i], file, "polygon[" + std::to_string(i) + "]");
    side = r.requiredString("side");
    if (side != "left" && side != "right") r.fail("side", "must be left or right" + gotValue(side));
  }
  p.side = side == "left" ? WrapSide::Left : WrapSide::Right;

  // Accept either orientation; indices in the output refer to the input order.
  p.order.resize(p.polygon.size());
  for (size_t i = 0; i < p.order.size(); ++i) p.order[i] = static_cast<int>(i);
  if (!isConvexCCW(p.polygon)) {
    std::reverse(p.polygon.begin(), p.polygon.end());
    std::reverse(p.order.begin(), p.order.end());
    if (!isConvexCCW(p.polygon))
      throw InputError(file, "polygon",
                       "is not convex (or has repeated or collinear vertices) (got " +
                           std::to_string(p.polygon.size()) + " vertices)");
  }
  if ((p.a - p.b).norm() == 0)
    throw InputError(
        file, "B",
        "coincides with A (got [" + formatNumber(p.b.x()) + ", " + formatNumber(p.b.y()) + "])");
  return p;
}

WrapProblem parseWrapText(const std::string& text, const std::string& source) {
  return parseWrapJson(parseJsonText(text, source), source);
}

WrapProblem loadWrapFile(const std::string& path) {
  return parseWrapText(readInputFile(path), path);
}

WrapSolution solveWrap(const WrapProblem& p, const std::string& file) {
  const auto chain = wrapChain(p.a, p.b, p.polygon, p.side);
  if (!chain)
    throw InputError(file, "A",
                     "A or B lies inside the polygon: no taut path goes round it (got A [" +
                         formatNumber(p.a.x()) + ", " + formatNumber(p.a.y()) + "], B [" +
                         formatNumber(p.b.x()) + ", " + formatNumber(p.b.y()) + "])");
  WrapSolution s;
  s.path.push_back(p.a);
  for (int v : *chain) {
    s.path.push_back(p.polygon[v]);
    s.contacts.push_back(p.order[v]);
  }
  s.path.push_back(p.b);
  s.length = chainLength(p.a, p.b, p.polygon, *chain);
  return s;
}

json wrapSolutionToJson(const WrapSolution& s) {
  json path = json::array();
  for (const Vec2& v : s.path) path.push_back({v.x(), v.y()});
  return json{{"path", path}, {"length", s.length}, {"contact_vertices", s.contacts}};
}

}  // namespace cablelab
