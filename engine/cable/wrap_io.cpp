#include "engine/cable/wrap_io.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

using nlohmann::json;

// Coordinates beyond this (m) would overflow squared lengths; like the statics input's bound.
constexpr double kMaxCoordinate = 1e9;

double number(const json& v, const std::string& file, const std::string& field) {
  if (!v.is_number()) throw InputError(file, field, "must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw InputError(file, field, "must be finite");
  if (std::abs(d) > kMaxCoordinate) throw InputError(file, field, "must be within +/-1e9 m");
  return d;
}

Vec2 vec2(const json& v, const std::string& file, const std::string& field) {
  if (!v.is_array() || v.size() != 2) throw InputError(file, field, "must be [x, y]");
  return Vec2(number(v[0], file, field + "[0]"), number(v[1], file, field + "[1]"));
}

}  // namespace

WrapProblem parseWrapJson(const json& in, const std::string& file) {
  if (!in.is_object()) throw InputError(file, "(json)", "must be an object");
  for (const char* key : {"A", "B", "polygon", "side"})
    if (!in.contains(key)) throw InputError(file, key, "is required");
  WrapProblem p;
  p.a = vec2(in["A"], file, "A");
  p.b = vec2(in["B"], file, "B");
  if (!in["polygon"].is_array() || in["polygon"].size() < 3)
    throw InputError(file, "polygon", "needs at least 3 vertices");
  for (size_t i = 0; i < in["polygon"].size(); ++i)
    p.polygon.push_back(vec2(in["polygon"][i], file, "polygon[" + std::to_string(i) + "]"));
  if (!in["side"].is_string() || (in["side"] != "left" && in["side"] != "right"))
    throw InputError(file, "side", "must be \"left\" or \"right\"");
  p.side = in["side"] == "left" ? WrapSide::Left : WrapSide::Right;

  // Accept either orientation; indices in the output refer to the input order.
  p.order.resize(p.polygon.size());
  for (size_t i = 0; i < p.order.size(); ++i) p.order[i] = static_cast<int>(i);
  if (!isConvexCCW(p.polygon)) {
    std::reverse(p.polygon.begin(), p.polygon.end());
    std::reverse(p.order.begin(), p.order.end());
    if (!isConvexCCW(p.polygon))
      throw InputError(file, "polygon", "is not convex (or has repeated or collinear vertices)");
  }
  if ((p.a - p.b).norm() == 0) throw InputError(file, "B", "coincides with A");
  return p;
}

WrapProblem parseWrapText(const std::string& text, const std::string& source) {
  json in;
  try {
    in = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(source, "(json)", std::string("not valid JSON: ") + e.what());
  }
  return parseWrapJson(in, source);
}

WrapSolution solveWrap(const WrapProblem& p, const std::string& file) {
  const auto chain = wrapChain(p.a, p.b, p.polygon, p.side);
  if (!chain)
    throw InputError(file, "A", "A or B lies inside the polygon: no taut path goes round it");
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
