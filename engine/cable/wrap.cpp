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

int tangentVertex(const Vec2& terminal, std::span<const Vec2> polygon, WrapSide side, bool into) {
  if (insideConvex(terminal, polygon)) return -1;
  const int n = static_cast<int>(polygon.size());
  // Mirror Right into Left: walking the path, the polygon must stay on the right (s = +1). Seen
  // from an outside point the polygon spans less than half a turn, so "more to the left" is a
  // total order: from a, the vertex with nothing on the left of a->v; into b, the vertex with
  // nothing on the left of v->b. Ties (collinear): the vertex farther from the terminal, so
  // collinear points never become wrap points.
  const double s = side == WrapSide::Right ? -1.0 : 1.0;
  int t = 0;
  for (int i = 1; i < n; ++i) {
    const double r = into ? -s * cross(terminal - polygon[t], polygon[i] - polygon[t])
                          : -s * cross(polygon[t] - terminal, polygon[i] - terminal);
    if (r < 0 ||
        (r == 0 && (polygon[i] - terminal).squaredNorm() > (polygon[t] - terminal).squaredNorm()))
      t = i;
  }
  return t;
}

double poseRounding(double scale) {
  // Box2D stores a body's position and angle as floats (2^-24 relative each); the point's
  // lever turns the angle's rounding into position (docs/model.md, "Coupling to Box2D").
  constexpr double kFloatRoundings = 8;
  return kFloatRoundings * std::ldexp(1.0, -24) * std::max(scale, 1.0);
}

int tangentVertexOnFace(const Vec2& terminal, std::span<const Vec2> polygon, WrapSide side,
                        bool into, double tolerance) {
  const int n = static_cast<int>(polygon.size());
  int face = -1;
  double nearest = tolerance;
  for (int i = 0; i < n; ++i) {
    const Vec2 edge = polygon[(i + 1) % n] - polygon[i];
    const double depth = cross(edge, terminal - polygon[i]) / edge.norm();  // > 0: inside
    if (depth <= 0) return -1;                                              // outside this face
    if (depth <= nearest) nearest = depth, face = i;
  }
  if (face < 0) return -1;
  // Walking with the polygon on the cable's right: `step` +1 reaches the face at polygon[face]
  // and leaves it at polygon[face + 1]; -1 the other way round.
  const bool forward = walkStep(side) > 0;
  return forward == into ? face : (face + 1) % n;
}

namespace {

// The tangent vertices of the taut path a -> polygon -> b on `side`: ta from a, tb into b.
// False when a terminal lies inside the polygon (no taut path round it exists).
bool tangentVertices(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon, WrapSide side,
                     int& ta, int& tb) {
  ta = tangentVertex(a, polygon, side, false);
  tb = tangentVertex(b, polygon, side, true);
  return ta >= 0 && tb >= 0;
}

}  // namespace

int walkStep(WrapSide side) {
  return side == WrapSide::Right ? 1 : -1;
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
  chain.clear();
  int ta, tb;
  if (!tangentVertices(a, b, polygon, side, ta, tb)) return std::nullopt;
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

}  // namespace cablelab
