// A cable end tied to the polygon pulley it winds round (tied_end.h, docs/cables.md).
#include "engine/cable/tied_end.h"

#include <algorithm>
#include <cmath>

#include "engine/cable/cable.h"
#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

WrapSide mirrored(WrapSide side) {
  return side == WrapSide::Right ? WrapSide::Left : WrapSide::Right;
}

}  // namespace

int tiedEndCorner(const Vec2& end, std::span<const Vec2> polygon, WrapSide side, bool& inside) {
  const int n = static_cast<int>(polygon.size());
  double size = 0;
  for (const Vec2& v : polygon) size = std::max(size, (v - polygon[0]).norm());
  const double tolerance = 1e-9 * size;
  // The edge nearest the end: the largest signed distance outside (positive = outside).
  int edge = -1;
  double outside = -1e300;
  for (int i = 0; i < n; ++i) {
    const Vec2 e = polygon[(i + 1) % n] - polygon[i];
    const double d = -cross(e, end - polygon[i]) / e.norm();
    if (d > outside) outside = d, edge = i;
  }
  if (outside > tolerance) return -1;
  inside = outside < -tolerance;
  // Where along the edge, walking it as the cable does (counter-clockwise for Right).
  const Vec2 e = polygon[(edge + 1) % n] - polygon[edge];
  const double t = std::clamp((end - polygon[edge]).dot(e) / e.squaredNorm(), 0.0, 1.0);
  const bool ccw = side == WrapSide::Right;
  const int first = ccw ? edge : (edge + 1) % n;
  const double along = (ccw ? t : 1 - t) * e.norm();
  // At the edge's first vertex itself: the cable arrives there along the edge before it.
  if (along > tolerance) return first;
  return ((ccw ? first - 1 : first + 1) % n + n) % n;
}

std::optional<double> wrapChainToTiedEnd(const Vec2& a, std::span<const Vec2> polygon,
                                         WrapSide side, int corner, double reference, int held,
                                         std::vector<int>& chain) {
  chain.clear();
  int ta = tangentVertex(a, polygon, side, false);
  if (ta < 0) ta = held;
  if (ta < 0) return std::nullopt;
  const int n = static_cast<int>(polygon.size()), step = walkStep(side);
  // The path turns at `corner` onto its edge: walkTurning's B is the edge's next vertex.
  int walk, loops;
  const double turn = walkTurning(a, polygon[(corner + step + n) % n], polygon, side, ta, corner,
                                  reference, walk, loops);
  const int count = walk + loops * n;
  if (turn <= kStraightWrapTurn || count <= 0) return std::min(turn, 0.0);
  for (int k = 0, i = ta; k < count; ++k, i = (i + step + n) % n) chain.push_back(i);
  return turn;
}

// A polygon pulley next to a terminal fixed on its own body, on or inside its hull, is a spool
// the cable is tied to: it is in the path from the start and never leaves it (the cable ends on
// it). Its turn starts from the turns it was wound with (0: the branch nearest no wrap).
void Cable::findTiedEnds() {
  if (pulleys_.empty()) return;
  auto tie = [](PulleyState& p, const WrapPoint& terminal, int end) {
    if (!p.polygon || p.autoSide || p.body != terminal.body || terminal.radius != 0 ||
        p.tiedEnd != 0)
      return;
    // Walking towards the end: the cable's own walk at the end, the mirrored one at the start.
    bool inside = false;
    const int corner =
        tiedEndCorner(terminal.local, p.local, end > 0 ? p.side : mirrored(p.side), inside);
    if (corner < 0) return;
    p.tiedEnd = end;
    p.tiedCorner = corner;
    p.tiedInside = inside;
    p.engaged = true;
    p.arc = 2 * M_PI * p.turns;
  };
  tie(pulleys_.back(), end_, 1);
  tie(pulleys_.front(), start_, -1);
}

// A and B: the points before and after the polygon in the path (one of them its tied end).
std::optional<double> Cable::tiedChain(const PulleyState& p, const Vec2& a, const Vec2& b,
                                       std::vector<int>& chain) const {
  // The corner the free part of the cable came over at the last update (path_ is that path).
  const int pulley = static_cast<int>(&p - pulleys_.data());
  int held = -1;
  for (size_t i = 0; i < path_.size(); ++i) {
    const WrapPoint& w = path_[p.tiedEnd > 0 ? i : path_.size() - 1 - i];
    if (w.pulley != pulley) continue;
    held = w.vertex;
    break;
  }
  std::optional<double> turn;
  if (p.tiedEnd > 0) {
    turn = wrapChainToTiedEnd(a, p.world, p.side, p.tiedCorner, p.arc, held, chain);
  } else {
    // The path from B back to the start, on the mirrored side, reversed.
    turn = wrapChainToTiedEnd(b, p.world, mirrored(p.side), p.tiedCorner, p.arc, held, chain);
    std::reverse(chain.begin(), chain.end());
  }
  // An end inside the hull is reached through its corner even when the cable has unwound past
  // it (a straight path would cross the polygon; through the corner the length stays continuous).
  if (turn && p.tiedInside && chain.empty()) chain.push_back(p.tiedCorner);
  return turn;
}

int Cable::tiedCornerWaiting(size_t segment, int& pulley) const {
  const int count = namedPulleys_;  // a polygon's second place is never tied
  if (count == 0) return -1;
  if (segment + 2 == path_.size() && pulleys_[count - 1].tiedEnd > 0 &&
      path_[segment].pulley != count - 1) {
    pulley = count - 1;
    return pulleys_[count - 1].tiedCorner;
  }
  if (segment == 0 && pulleys_.front().tiedEnd < 0 && path_[1].pulley != 0) {
    pulley = 0;
    return pulleys_.front().tiedCorner;
  }
  return -1;
}

}  // namespace cablelab
