#include "engine/cable/wrap_hold.h"

#include <algorithm>
#include <cmath>

#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

// m: how much longer the rope may get where the next vertex joins a held end. A vertex that
// crosses the segment joins on it, at an event; one that lies off it crossed nothing: a hooked
// triangle's end doubled back round its corner until its turn fell below half a turn within one
// update, and its next corner, on the wrap side all along, joined 0.1-0.28 m off the old path.
constexpr double kHeldJoinDetour = 0.01;

// The turn at end vertex `at` of a chain between its chain neighbour `before` and the terminal
// `b` (walking the path), on the branch nearest `previous`.
double endTurn(const Vec2& b, std::span<const Vec2> polygon, WrapSide side, int before, int at,
               bool into, double previous) {
  const Vec2 &p = polygon[before], &q = polygon[at];
  return into ? continuedPointTurn(q - p, b - q, side, previous)
              : continuedPointTurn(q - b, p - q, side, previous);
}

// The turn (rad) along a held chain of `count` >= 2 vertices from `ta`: the held ends' turns,
// continued over time, and the corners between them (laps included).
double heldChainTurn(std::span<const Vec2> polygon, WrapSide side, int ta, int count,
                     double turnFrom, double turnInto) {
  const int n = static_cast<int>(polygon.size()), step = walkStep(side);
  double turn = turnFrom + turnInto;
  for (int k = 1, i = (ta + step + n) % n; k + 1 < count; ++k, i = (i + step + n) % n) {
    const Vec2 &v = polygon[i], &before = polygon[(i - step + n) % n];
    turn += continuedPointTurn(v - before, polygon[(i + step + n) % n] - v, side, 0.0);
  }
  return turn;
}

// The end of the chain into `b` continued from `t` (its last vertex at the last update) with the
// turn at it `turn` (continued over time); `count`, the chain's vertices, follows each leave and
// join, and the last vertex does not leave here. The from-end is the same walk mirrored (`into`
// false: `b` is the start terminal and the walk goes the other way).
int continuedEnd(const Vec2& b, std::span<const Vec2> polygon, WrapSide side, int t, bool into,
                 double& turn, int& count) {
  const int n = static_cast<int>(polygon.size());
  const int step = into ? walkStep(side) : -walkStep(side);
  auto turnAt = [&](int before, int at, double previous) {
    return endTurn(b, polygon, side, before, at, into, previous);
  };
  // A chain of one vertex keeps the turn from one terminal to the other (wrapChainHeld).
  if (count > 1) turn = turnAt((t - step + n) % n, t, turn);
  // Leave: the end vertex no longer bends the path (the last one leaves with the whole chain,
  // when the turn from one terminal to the other goes below zero). Counted, not bounded by the
  // other end's vertex: a chain of one vertex and a lap has that vertex at both ends.
  for (; turn < 0 && count > 1; --count) {
    t = (t - step + n) % n;
    turn = turnAt((t - step + n) % n, t, 0.0);
  }
  // Join: the next vertex reaches the wrap side of the segment to an outside terminal, between
  // the end vertex and the terminal (behind the end vertex or beyond the terminal, on the line's
  // extension, it crossed no segment: joined, the rope would double back on the edge or round the
  // far side). Through the hull (the terminal went in one side and out of another), doubled back
  // round the end vertex, or where the rope from the next vertex would cut the hull (the terminal
  // came out by the edge behind the end vertex, the hull on the segment's wrap side), the segment
  // holds its vertex. So it does where the next vertex lies off the segment (kHeldJoinDetour): it
  // did not cross it, the end's rope had doubled back (a triangle hooked past the end anchor).
  if (turn >= M_PI || insideConvex(b, polygon)) return t;
  for (int k = 0; k < n; ++k) {
    const int next = (t + step + n) % n;
    const double across = into ? wrapSideDistance(polygon[t], b, polygon[next], side)
                               : -wrapSideDistance(polygon[t], b, polygon[next], side);
    const double along = (polygon[next] - polygon[t]).dot(b - polygon[t]);
    const bool ahead = along > 0 && along < (b - polygon[t]).squaredNorm();
    const double detour =
        (polygon[next] - polygon[t]).norm() + (b - polygon[next]).norm() - (b - polygon[t]).norm();
    if (segmentCutsPolygon(polygon[t], b, polygon) || across <= 0 || !ahead ||
        segmentCutsPolygon(polygon[next], b, polygon) || detour > kHeldJoinDetour)
      break;
    t = next;
    ++count;
    turn = turnAt((t - step + n) % n, t, 0.0);
  }
  return t;
}

}  // namespace

bool commonTangent(std::span<const Vec2> first, WrapSide firstSide, std::span<const Vec2> second,
                   WrapSide secondSide, int& from, int& into) {
  // Walking the segment first[i] -> second[j], each polygon must lie on its wrap side of it (on
  // the right for Left): the supporting line of both. Every pair is tried (a few vertices each);
  // among collinear candidates the longest segment, so that collinear vertices are not wrap
  // points (as in tangentVertex).
  const double s1 = firstSide == WrapSide::Right ? -1.0 : 1.0;
  const double s2 = secondSide == WrapSide::Right ? -1.0 : 1.0;
  double scale = 0;
  for (const Vec2& v : first) scale = std::max(scale, (v - second[0]).norm());
  for (const Vec2& v : second) scale = std::max(scale, (v - first[0]).norm());
  const double eps = 1e-12 * scale * scale;
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

std::optional<double> wrapChainHeld(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                                    WrapSide side, double reference, bool mayHoldFrom,
                                    bool mayHoldInto, ChainHold& hold, std::vector<int>& chain) {
  chain.clear();
  int tangentFrom = tangentVertex(a, polygon, side, false);
  int tangentInto = tangentVertex(b, polygon, side, true);
  // A terminal that may not hold the chain lies on a face, only Box2D's float pose inside it (a
  // weight hanging along a square's side): it is outside, its rope runs along the face. One that
  // may hold it lies there as it enters, the step cut at its crossing: it holds from then on
  // (docs/polygon_friction.md, "Elastic cables").
  auto onFace = [&](const Vec2& terminal, bool into) {
    double scale = terminal.norm();
    for (const Vec2& v : polygon) scale = std::max(scale, v.norm());
    return tangentVertexOnFace(terminal, polygon, side, into, poseRounding(scale));
  };
  if (tangentFrom < 0 && !mayHoldFrom) tangentFrom = onFace(a, false);
  if (tangentInto < 0 && !mayHoldInto) tangentInto = onFace(b, true);
  // The chain's last vertex at the last update: `count` vertices from its first.
  const int n = static_cast<int>(polygon.size()), step = walkStep(side);
  const int last = hold.from < 0 ? -1 : (hold.from + (hold.count - 1) * step % n + n) % n;
  // While one end is held the other follows the old chain too: its tangent vertex can pass the
  // held end (the rope pulled into the hull), where the walk between them would be a lap long.
  const bool holding =
      hold.from >= 0 && (hold.holdingFrom || hold.holdingInto || (tangentFrom < 0 && mayHoldFrom) ||
                         (tangentInto < 0 && mayHoldInto));
  // A hold starts from the turn the end vertex has now (less than half a turn: the terminal has
  // just gone in).
  if (holding && !hold.holdingFrom) hold.turnFrom = 0;
  if (holding && !hold.holdingInto) hold.turnInto = 0;
  hold.holdingFrom = hold.holdingInto = holding;
  int ta = tangentFrom, tb = tangentInto;
  int count = hold.count;
  // A single vertex turns the path from a to b, that turn continued over time (both ends hold it);
  // it leaves with the whole chain.
  auto singleTurn = [&](int v) {
    hold.turnFrom = hold.turnInto =
        continuedPointTurn(polygon[v] - a, b - polygon[v], side, reference);
  };
  if (holding) {
    if (count == 1) singleTurn(last);
    tb = continuedEnd(b, polygon, side, last, true, hold.turnInto, count);
    if (count == 1) singleTurn(tb);
    ta = continuedEnd(a, polygon, side, hold.from, false, hold.turnFrom, count);
  }
  if (ta < 0 || tb < 0) {
    hold = ChainHold{};
    return std::nullopt;
  }
  double turn;
  if (holding && count == 1) {
    turn = hold.turnInto;
  } else if (holding) {
    turn = heldChainTurn(polygon, side, ta, count, hold.turnFrom, hold.turnInto);
  } else {
    int walk, loops;
    turn = walkTurning(a, b, polygon, side, ta, tb, reference, walk, loops);
    count = walk + loops * n;
  }
  // Let go where the held ends are the taut path's own again (a chain of `count` vertices from
  // them is then the one walkTurning gives for this turn).
  if (holding && ta == tangentFrom && tb == tangentInto && hold.turnInto < M_PI &&
      hold.turnFrom < M_PI)
    hold.holdingFrom = hold.holdingInto = false;
  if (turn > kStraightWrapTurn)
    for (int k = 0, i = ta; k < count; ++k, i = (i + step + n) % n) chain.push_back(i);
  hold.from = chain.empty() ? -1 : chain.front();
  hold.count = static_cast<int>(chain.size());
  if (chain.empty()) hold.holdingFrom = hold.holdingInto = false;
  return turn > kStraightWrapTurn ? turn : std::min(turn, 0.0);
}

}  // namespace cablelab
