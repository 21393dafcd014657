#include "engine/cable/wrap.h"

#include <algorithm>

namespace cablelab {

namespace {

// Points closer than this to a hull edge's line count as collinear and are not wrap points.
constexpr double kCollinear = 1e-12;

}  // namespace

double wrapSideDistance(const Vec2& a, const Vec2& b, const Vec2& p, WrapSide side) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len == 0) return -(p - a).norm();
  const double left = cross(d, p - a) / len;
  // Left: the cable goes round the pulley's left flank, so a pulley is wrapped once it has
  // crossed to the left of the straight cable (and then lies on the bent cable's right).
  return side == WrapSide::Right ? -left : left;
}

bool segmentCutsPolygon(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon) {
  // Clip the segment against every edge's inner half-plane (Cyrus-Beck).
  double t0 = 0, t1 = 1;
  const Vec2 d = b - a;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2& p = polygon[i];
    const Vec2 e = polygon[(i + 1) % n] - p;
    // Inside: cross(e, x - p) > 0.
    const double num = cross(e, a - p);
    const double den = cross(e, d);
    if (std::abs(den) < 1e-300) {
      if (num <= 0) return false;
      continue;
    }
    const double t = -num / den;
    if (den > 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 >= t1) return false;
  }
  return t1 - t0 > 1e-12;
}

std::optional<std::vector<int>> wrapChain(const Vec2& a, const Vec2& b,
                                          std::span<const Vec2> polygon, WrapSide side) {
  std::vector<int> chain;
  if (!wrapChain(a, b, polygon, side, chain)) return std::nullopt;
  return chain;
}

bool wrapChain(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon, WrapSide side,
               std::vector<int>& chain) {
  chain.clear();
  const int n = static_cast<int>(polygon.size());
  const Vec2 ab = b - a;
  const double scale = std::max({ab.norm(), (polygon[0] - a).norm(), 1e-300});
  const double eps = kCollinear * scale * scale;
  // The polygon bends the path only if a vertex lies strictly on the wrap side of line ab.
  bool bends = false;
  for (const Vec2& v : polygon) bends |= wrapSideDistance(a, b, v, side) * scale > eps;
  if (!bends) return true;

  // Mirror Right into Left: walking the path, the polygon must stay on the right (s = +1).
  const double s = side == WrapSide::Right ? -1.0 : 1.0;
  auto right = [&](const Vec2& from, const Vec2& to, const Vec2& p) {
    return -s * cross(to - from, p - from);
  };
  // A terminal inside the polygon has no taut path round it.
  auto insidePolygon = [&](const Vec2& p) {
    for (int i = 0; i < n; ++i)
      if (cross(polygon[(i + 1) % n] - polygon[i], p - polygon[i]) <= 0) return false;
    return true;
  };
  if (insidePolygon(a) || insidePolygon(b)) return false;
  // Tangent vertices by one sweep each (seen from an outside point the polygon spans less than
  // half a turn, so "more to the left" is a total order): from a, the vertex with nothing on the
  // left of a->v; into b, the vertex with nothing on the left of v->b. Ties (collinear): the
  // vertex farther from the terminal, so collinear points never become wrap points.
  int ta = 0, tb = 0;
  for (int i = 1; i < n; ++i) {
    const double r = right(a, polygon[ta], polygon[i]);
    if (r < 0 || (r == 0 && (polygon[i] - a).squaredNorm() > (polygon[ta] - a).squaredNorm()))
      ta = i;
  }
  for (int i = 1; i < n; ++i) {
    const double r = right(polygon[tb], b, polygon[i]);
    if (r < 0 || (r == 0 && (polygon[i] - b).squaredNorm() > (polygon[tb] - b).squaredNorm()))
      tb = i;
  }
  // Walk the boundary with the polygon on the right: clockwise for Left, counter-clockwise for
  // Right.
  const int stepDir = side == WrapSide::Right ? 1 : -1;
  for (int i = ta;; i = (i + stepDir + n) % n) {
    chain.push_back(i);
    if (i == tb || static_cast<int>(chain.size()) > n) break;
  }
  return true;
}

double chainLength(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                   const std::vector<int>& chain) {
  double total = 0;
  Vec2 prev = a;
  for (int i : chain) {
    total += (polygon[i] - prev).norm();
    prev = polygon[i];
  }
  return total + (b - prev).norm();
}

}  // namespace cablelab
