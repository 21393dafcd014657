#include "engine/cable/wrap_hold.h"

#include <algorithm>
#include <cmath>

#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

// The turn at end vertex `at` of a chain between its chain neighbour `before` and the terminal
// `b` (walking the path), on the branch nearest `previous`.
double endTurn(const Vec2& b, std::span<const Vec2> polygon, WrapSide side, int before, int at,
               bool into, double previous) {
  const Vec2 &p = polygon[before], &q = polygon[at];
  return into ? continuedPointTurn(q - p, b - q, side, previous)
              : continuedPointTurn(q - b, p - q, side, previous);
}

// The whole turns (rad) by which a held end's turn, continued over time, differs from the one
// walkTurning sums there (within half a turn of zero).
double heldWholeTurns(const Vec2& b, std::span<const Vec2> polygon, WrapSide side, int t, bool into,
                      double turn) {
  const int n = static_cast<int>(polygon.size());
  const int step = into ? walkStep(side) : -walkStep(side);
  const double raw = endTurn(b, polygon, side, (t - step + n) % n, t, into, 0.0);
  return 2 * M_PI * std::round((turn - raw) / (2 * M_PI));
}

// The end of the chain into `b` continued from `t` (its last vertex at the last update) with the
// turn at it `turn` (continued over time); the chain's other end `first` bounds the shrinking.
// The from-end is the same walk mirrored (`into` false: `b` is the start terminal and the walk
// goes the other way).
int continuedEnd(const Vec2& b, std::span<const Vec2> polygon, WrapSide side, int t, int first,
                 bool into, double& turn) {
  const int n = static_cast<int>(polygon.size());
  const int step = into ? walkStep(side) : -walkStep(side);
  auto turnAt = [&](int before, int at, double previous) {
    return endTurn(b, polygon, side, before, at, into, previous);
  };
  turn = turnAt((t - step + n) % n, t, turn);
  // Leave: the end vertex no longer bends the path (one whose chain neighbour is the other end
  // leaves with the whole chain, walkTurning).
  for (int k = 0; k < n && turn < 0 && t != first; ++k) {
    t = (t - step + n) % n;
    turn = turnAt((t - step + n) % n, t, 0.0);
  }
  // Join: the next vertex reaches the wrap side of the segment to an outside terminal. Through
  // the hull (the terminal went in one side and out of another) or doubled back round the end
  // vertex, the segment holds its vertex.
  if (turn >= M_PI || insideConvex(b, polygon)) return t;
  for (int k = 0; k < n; ++k) {
    const int next = (t + step + n) % n;
    const double across = into ? wrapSideDistance(polygon[t], b, polygon[next], side)
                               : -wrapSideDistance(polygon[t], b, polygon[next], side);
    if (segmentCutsPolygon(polygon[t], b, polygon) || across <= 0) break;
    t = next;
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
  const int tangentFrom = tangentVertex(a, polygon, side, false);
  const int tangentInto = tangentVertex(b, polygon, side, true);
  // While one end is held the other follows the old chain too: its tangent vertex can pass the
  // held end (the rope pulled into the hull), where the walk between them would be a lap long.
  const bool holding = hold.from >= 0 && hold.into >= 0 &&
                       (hold.holdingFrom || hold.holdingInto || (tangentFrom < 0 && mayHoldFrom) ||
                        (tangentInto < 0 && mayHoldInto));
  // A hold starts from the turn the end vertex has now (less than half a turn: the terminal has
  // just gone in).
  if (holding && !hold.holdingFrom) hold.turnFrom = 0;
  if (holding && !hold.holdingInto) hold.turnInto = 0;
  hold.holdingFrom = hold.holdingInto = holding;
  int ta = tangentFrom, tb = tangentInto;
  bool single = false;
  double singleWhole = 0;
  if (holding) {
    // A single vertex turns the path from a to b; it leaves with the whole chain (walkTurning).
    single = hold.from == hold.into && reference < 2 * M_PI;
    if (single) {
      ta = tb = hold.into;
      const Vec2 in = polygon[tb] - a, out = b - polygon[tb];
      hold.turnInto = continuedPointTurn(in, out, side, hold.turnInto);
      const double raw = continuedPointTurn(in, out, side, 0.0);
      singleWhole = 2 * M_PI * std::round((hold.turnInto - raw) / (2 * M_PI));
    } else {
      tb = continuedEnd(b, polygon, side, hold.into, hold.from, true, hold.turnInto);
      ta = continuedEnd(a, polygon, side, hold.from, tb, false, hold.turnFrom);
    }
  }
  if (ta < 0 || tb < 0) {
    hold = ChainHold{};
    return std::nullopt;
  }
  // Let go where the held ends are the taut path's own again.
  if (holding && ta == tangentFrom && tb == tangentInto && hold.turnInto < M_PI &&
      (single || hold.turnFrom < M_PI))
    hold.holdingFrom = hold.holdingInto = false;
  const int n = static_cast<int>(polygon.size()), step = walkStep(side);
  // A held end doubled back past half a turn turns by more than walkTurning's sum there: the
  // chain has as many loops fewer as that sum misses whole turns.
  double whole = singleWhole;
  if (holding && !single && ta != tb) {
    whole += heldWholeTurns(b, polygon, side, tb, true, hold.turnInto);
    whole += heldWholeTurns(a, polygon, side, ta, false, hold.turnFrom);
  } else if (holding && !single) {
    // Whole laps from one vertex: walkTurning sums the turn from a to b there, the held ends
    // turn into the lap and out of it, and the corner's own turn is counted twice by them.
    const Vec2 &v = polygon[ta], &before = polygon[(ta - step + n) % n];
    const Vec2& after = polygon[(ta + step + n) % n];
    const double corner = continuedPointTurn(v - before, after - v, side, 0.0);
    const double raw = continuedPointTurn(v - a, b - v, side, 0.0);
    whole += 2 * M_PI * std::round((hold.turnFrom + hold.turnInto - corner - raw) / (2 * M_PI));
  }
  int walk, loops;
  const double turn =
      walkTurning(a, b, polygon, side, ta, tb, reference - whole, walk, loops) + whole;
  if (turn > kStraightWrapTurn) {
    for (int k = 0, i = ta; k < walk; ++k, i = (i + step + n) % n) chain.push_back(i);
    for (int k = 0; k < loops * n; ++k) chain.push_back((chain.back() + step + n) % n);
  }
  hold.from = chain.empty() ? -1 : chain.front();
  hold.into = chain.empty() ? -1 : chain.back();
  if (chain.empty()) hold.holdingFrom = hold.holdingInto = false;
  return turn;
}

}  // namespace cablelab
