#include "engine/cable/wrap.h"

#include <algorithm>
#include <cmath>

namespace cablelab {

namespace {

// Points closer than this to a hull edge's line count as collinear and are not wrap points.
constexpr double kCollinear = 1e-12;
// A wrap that turns the path by less than this (rad) is straight: no vertex is a wrap point.
constexpr double kStraightTurn = kStraightWrapTurn;

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

double continuedPointTurn(const Vec2& in, const Vec2& out, WrapSide side, double previous) {
  const double s = side == WrapSide::Right ? -1.0 : 1.0;
  const double raw = -s * std::atan2(cross(in, out), in.dot(out));
  return raw + 2 * M_PI * std::round((previous - raw) / (2 * M_PI));
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

bool insideConvex(const Vec2& p, std::span<const Vec2> polygon) {
  const int n = static_cast<int>(polygon.size());
  for (int i = 0; i < n; ++i)
    if (cross(polygon[(i + 1) % n] - polygon[i], p - polygon[i]) <= 0) return false;
  return true;
}

namespace {

// The tangent vertex of the taut path from `a` round the polygon on `side` (walking the path the
// polygon stays on the right for Left, s = +1), or into `b` (`into`); -1 when the terminal lies
// inside the polygon (no taut path round it exists). Seen from an outside point the polygon spans
// less than half a turn, so "more to the left" is a total order: from a, the vertex with nothing
// on the left of a->v; into b, the vertex with nothing on the left of v->b. Ties (collinear): the
// vertex farther from the terminal, so collinear points never become wrap points.
int tangentVertex(const Vec2& terminal, std::span<const Vec2> polygon, WrapSide side, bool into) {
  if (insideConvex(terminal, polygon)) return -1;
  const int n = static_cast<int>(polygon.size());
  const double s = side == WrapSide::Right ? -1.0 : 1.0;
  int t = 0;
  for (int i = 1; i < n; ++i) {
    const double r = into ? -s * cross(terminal - polygon[t], polygon[i] - polygon[t])
                          : -s * cross(polygon[t] - terminal, polygon[i] - terminal);
    if (r < 0 || (r == 0 && (polygon[i] - terminal).squaredNorm() >
                                (polygon[t] - terminal).squaredNorm()))
      t = i;
  }
  return t;
}

// The tangent vertices of the taut path a -> polygon -> b on `side`: ta from a, tb into b.
// False when a terminal lies inside the polygon (no taut path round it exists).
bool tangentVertices(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon, WrapSide side,
                     int& ta, int& tb) {
  ta = tangentVertex(a, polygon, side, false);
  tb = tangentVertex(b, polygon, side, true);
  return ta >= 0 && tb >= 0;
}

// The walk round the boundary with the polygon on the right (clockwise for Left,
// counter-clockwise for Right): +1 or -1 per vertex.
int walkStep(WrapSide side) {
  return side == WrapSide::Right ? 1 : -1;
}

}  // namespace

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
  int ta, tb;
  if (!tangentVertices(a, b, polygon, side, ta, tb)) return false;
  const int stepDir = walkStep(side);
  for (int i = ta;; i = (i + stepDir + n) % n) {
    chain.push_back(i);
    if (i == tb || static_cast<int>(chain.size()) > n) break;
  }
  return true;
}

double walkTurning(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon, WrapSide side,
                   int ta, int tb, double reference, int& walk, int& loops) {
  const int n = static_cast<int>(polygon.size()), stepDir = walkStep(side);
  // The walk ta -> tb and the angle the path turns along it, in the wrap sense (clockwise for
  // Left): every turn on it is >= 0 but possibly the one of a single vertex, so it lies in
  // (-pi, 2 pi]. The wrap is that plus whole turns: the branch nearest the reference.
  const double s = side == WrapSide::Right ? -1.0 : 1.0;
  double walkTurn = 0;
  Vec2 from = a;
  walk = 0;
  for (int i = ta;; i = (i + stepDir + n) % n) {
    ++walk;
    const Vec2 in = polygon[i] - from;
    from = polygon[i];
    const Vec2 out = (i == tb ? b : polygon[(i + stepDir + n) % n]) - from;
    walkTurn -= s * std::atan2(cross(in, out), in.dot(out));
    if (i == tb || walk > n) break;
  }
  const double whole = std::round((reference - walkTurn) / (2 * M_PI));
  const double turn = walkTurn + 2 * M_PI * whole;
  loops = static_cast<int>(whole);
  if (turn <= kStraightTurn) return std::min(turn, 0.0);
  return turn;
}

std::optional<double> wrapChainTurning(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                                       WrapSide side, double reference, std::vector<int>& chain) {
  return wrapChainHolding(a, b, polygon, side, reference, -1, -1, chain);
}

std::optional<double> wrapChainHolding(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                                       WrapSide side, double reference, int heldFrom,
                                       int heldInto, std::vector<int>& chain) {
  chain.clear();
  int ta = tangentVertex(a, polygon, side, false), tb = tangentVertex(b, polygon, side, true);
  if (ta < 0) ta = heldFrom;
  if (tb < 0) tb = heldInto;
  if (ta < 0 || tb < 0) {
    // Nothing held (the polygon is joining): the corner deepest on the wrap side of the segment
    // a-b, the one that crossed it, so that the join happens on the old path.
    int deepest = -1;
    double depth = 0;
    for (int i = 0; i < static_cast<int>(polygon.size()); ++i) {
      const double d = wrapSideDistance(a, b, polygon[i], side);
      if (d > depth) depth = d, deepest = i;
    }
    if (ta < 0) ta = deepest;
    if (tb < 0) tb = deepest;
  }
  if (ta < 0 || tb < 0) return std::nullopt;
  const int n = static_cast<int>(polygon.size()), stepDir = walkStep(side);
  int walk, loops;
  const double turn = walkTurning(a, b, polygon, side, ta, tb, reference, walk, loops);
  if (turn <= kStraightTurn) return turn;  // straight: the chain is empty
  for (int k = 0, i = ta; k < walk; ++k, i = (i + stepDir + n) % n) chain.push_back(i);
  // More than the walk: whole loops round the polygon, ending at tb again.
  for (int k = 0; k < loops * n; ++k) chain.push_back((chain.back() + stepDir + n) % n);
  return turn;
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

bool commonTangent(std::span<const Vec2> first, WrapSide firstSide, std::span<const Vec2> second,
                   WrapSide secondSide, int& from, int& into) {
  // Walking the segment first[i] -> second[j], each polygon must lie on its wrap side of it
  // (on the right for Left): the supporting line of both. Every pair is tried (at most 8 x 8
  // vertices); among collinear candidates the longest segment, so that collinear vertices are
  // not wrap points (as in tangentVertex).
  const double s1 = firstSide == WrapSide::Right ? -1.0 : 1.0;
  const double s2 = secondSide == WrapSide::Right ? -1.0 : 1.0;
  double scale = 0;
  for (const Vec2& v : first) scale = std::max(scale, (v - second[0]).norm());
  for (const Vec2& v : second) scale = std::max(scale, (v - first[0]).norm());
  const double eps = kCollinear * scale * scale;
  double best = -1;
  for (size_t i = 0; i < first.size(); ++i)
    for (size_t j = 0; j < second.size(); ++j) {
      const Vec2 d = second[j] - first[i];
      const double length = d.squaredNorm();
      if (!(length > 0) || length <= best) continue;
      bool supports = true;
      for (const Vec2& v : first) supports &= s1 * cross(d, v - first[i]) <= eps;
      for (const Vec2& v : second) supports &= s2 * cross(d, v - first[i]) <= eps;
      if (!supports) continue;
      best = length;
      from = static_cast<int>(i);
      into = static_cast<int>(j);
    }
  return best > 0;
}

}  // namespace cablelab
