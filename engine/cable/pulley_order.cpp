// The order in which the path meets its pulleys (docs/knocks.md, "Flung past a neighbour").
//
// A disengaged pulley joins the segment between its engaged neighbours in the scene's order. Two
// free polygons riding in one rope's loops knock and sling each other about: a polygon that left
// the rope came down on another segment of it (past its neighbour, on its neighbour's corner),
// which its place in the order never let it join, and the rope went through it. A free polygon
// (one-sided, on a moving body, not gripping, not tied) joins any other segment it crosses, on
// the old path as at its own (the World locates the crossing), and takes its place in the order
// there. It wraps on the side it came from, as an auto pulley does: coming down on the rope from
// the side it was not wrapped on, it went through. Off the path its place changes neither the
// length nor J. On the path, barely bending the rope where it rides its neighbour's hull, it
// moves its place to a segment it crosses where that moves the length by a fraction of a mm;
// wedged between two strands (moving would leave the old strand across it), its second place
// joins the strand it crosses, and the rope bends round it at both, whatever lies between the
// two strands (a neighbouring polygon's loop, a point's bend) and however deep its own wrap.
#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/cable/cable.h"
#include "engine/cable/wrap.h"

namespace cablelab {

bool Cable::joinsAnySegment(int j) const {
  const PulleyState& p = pulleys_[j];
  return p.polygon && p.body >= 0 && !p.autoSide && !p.grips && p.tiedEnd == 0 &&
         p.side != WrapSide::Threaded;
}

bool Cable::chainEdge(size_t i) const {
  const WrapPoint &a = path_[i], &b = path_[i + 1];
  return a.kind == WrapPoint::Kind::Vertex && b.kind == WrapPoint::Kind::Vertex &&
         a.pulley == b.pulley;
}

namespace {

// A join the World did not locate, or a polygon moving its place, is made only where it moves
// the length by less than this (m): half the 1 mm a wrap change off the old path is reported at
// (Cable::kLengthJump).
constexpr double kCrossedJoinDetour = 5e-4;

// How much longer the path a -> polygon -> b is than a -> b, wrapped on `side` (infinite where
// no taut path exists: a terminal inside the hull).
double crossedJoinDetour(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                         WrapSide side) {
  std::vector<int> chain;
  if (!wrapChain(a, b, polygon, side, chain)) return 1e300;
  return chainLength(a, b, polygon, chain) - (b - a).norm();
}

// The path indices of pulley j's first and last points (0, 0: not on the path).
std::pair<size_t, size_t> placeOnPath(std::span<const WrapPoint> path, int j) {
  size_t first = 0, last = 0;
  for (size_t i = 1; i + 1 < path.size(); ++i)
    if (path[i].pulley == j) {
      if (!first) first = i;
      last = i;
    }
  return {first, last};
}

// How much longer the path is for pulley j's chain than straight between its neighbours.
double ownWrapDetour(std::span<const WrapPoint> path, int j) {
  const auto [first, last] = placeOnPath(path, j);
  if (!first) return 1e300;
  const WrapPoint &from = path[first - 1], &to = path[last + 1];
  const Vec2 start = from.leaving();
  const Vec2 end = to.arriving();
  Vec2 at = start;
  double along = 0;
  for (size_t i = first; i <= last; ++i) {
    along += (path[i].world - at).norm();
    at = path[i].world;
  }
  return along + (end - at).norm() - (end - start).norm();
}

// Polygon q's chain (its vertices on the path) is the one between `from` and `to`.
bool chainKeptBetween(std::span<const WrapPoint> path, int q, std::span<const Vec2> polygon,
                      WrapSide side, const Vec2& from, const Vec2& to) {
  std::vector<int> now, then;
  for (const WrapPoint& w : path)
    if (w.pulley == q && w.kind == WrapPoint::Kind::Vertex) now.push_back(w.vertex);
  return wrapChain(from, to, polygon, side, then) && then == now;
}

}  // namespace

void Cable::addSecondPlaces() {
  for (int j = 0; j < namedPulleys_; ++j) {
    if (!joinsAnySegment(j)) continue;
    PulleyState second = pulleys_[j];
    second.engaged = false;
    second.arc = 0;
    second.secondPlace = true;
    second.twin = j;
    pulleys_[j].twin = static_cast<int>(pulleys_.size());
    pulleys_.push_back(std::move(second));
    order_.push_back(pulleys_[j].twin);
    rank_.push_back(static_cast<int>(order_.size()) - 1);
  }
}

void Cable::placeAfterSegment(int j, size_t i) {
  order_.erase(order_.begin() + rank_[j]);
  const int after = path_[i].pulley;
  order_.insert(after < 0 ? order_.begin() : std::find(order_.begin(), order_.end(), after) + 1, j);
  for (size_t r = 0; r < order_.size(); ++r) rank_[order_[r]] = static_cast<int>(r);
}

// Free polygon j: off the path, or on it where it barely bends the rope (above).
bool Cable::joinCrossedSegment(int j) {
  PulleyState& p = pulleys_[j];
  std::vector<PulleyState::SegmentDepth> before;
  std::swap(before, p.segmentDepths);
  p.segmentDepths.clear();
  int join = -1, joining = j;
  WrapSide joinSide = p.side;
  // Its own segment (from the path point before it in the order) is joinRound's; on the path,
  // the segments into, along and out of its chain are its own.
  size_t host = 0;
  while (host + 2 < path_.size() && rank_[path_[host + 1].pulley] < rank_[j]) ++host;
  // On the path, it moves its place only where that moves the length by less than
  // kCrossedJoinDetour (it barely bends the rope at either place): where the two chains of a pair
  // in one rope's loops meet, a polygon riding the other's hull comes off its corner as it crosses
  // the rope going into the other (docs/knocks.md, "Riding its neighbour's hull").
  const bool onPath = p.engaged;
  // Its place on the path (first = 0: off it), and the ends of the straight rope that moving
  // would leave there.
  const std::pair<size_t, size_t> place = placeOnPath(path_, j);
  const size_t first = place.first, last = place.second;
  Vec2 oldFrom = Vec2::Zero(), oldTo = Vec2::Zero();
  if (first) {
    const WrapPoint &prev = path_[first - 1], &next = path_[last + 1];
    oldFrom = prev.leaving();
    oldTo = next.arriving();
  }
  // Joining segment i (wrapped on `side`), the neighbouring polygons there, and at its old place
  // if it moves, keep their chains: its detours are all the length moves by.
  auto neighboursKept = [&](size_t i, WrapSide side, bool moving) {
    std::vector<int> chain;
    const WrapPoint &wa = path_[i], &wb = path_[i + 1];
    const Vec2 a = wa.leaving();
    const Vec2 b = wb.arriving();
    if (!wrapChain(a, b, p.world, side, chain) || chain.empty()) return false;
    auto kept = [&](const WrapPoint& end, const Vec2& from, const Vec2& to) {
      if (end.kind != WrapPoint::Kind::Vertex) return true;
      const PulleyState& q = pulleys_[end.pulley];
      return chainKeptBetween(path_, end.pulley, q.world, q.side, from, to);
    };
    // Where the path leaves the point before path_[k]'s polygon, and reaches the one after it
    // (an end of the path, an anchor, has none: its own point, which kept() does not read).
    auto before = [&](size_t k) {
      if (k == 0) return path_[0].world;
      while (k > 1 && path_[k - 1].pulley == path_[k].pulley) --k;
      const WrapPoint& w = path_[k - 1];
      return w.leaving();
    };
    auto after = [&](size_t k) {
      if (k + 1 >= path_.size()) return path_.back().world;
      while (k + 2 < path_.size() && path_[k + 1].pulley == path_[k].pulley) ++k;
      const WrapPoint& w = path_[k + 1];
      return w.arriving();
    };
    if (!kept(wa, before(i), p.world[chain.front()]) ||
        !kept(wb, p.world[chain.back()], after(i + 1)))
      return false;
    if (!first || !moving) return true;  // off the path, or its old place kept
    return kept(path_[first - 1], before(first - 1), oldTo) &&
           kept(path_[last + 1], oldFrom, after(last + 1));
  };
  double own = -1;
  for (size_t i = 0; i + 1 < path_.size(); ++i) {
    if (chainEdge(i)) continue;
    const WrapPoint &wa = path_[i], &wb = path_[i + 1];
    if (onPath && (wa.pulley == j || wb.pulley == j ||
                   (p.twin >= 0 && (wa.pulley == p.twin || wb.pulley == p.twin))))
      continue;
    if (besideItsOtherPlace(j, wa, wb)) continue;
    const Vec2 a = wa.leaving();
    const Vec2 b = wb.arriving();
    double left = -1e300, right = -1e300;
    for (const Vec2& v : p.world) {
      left = std::max(left, wrapSideDistance(a, b, v, WrapSide::Left));
      right = std::max(right, wrapSideDistance(a, b, v, WrapSide::Right));
    }
    // A segment is named by the pulleys at its ends (-1: an anchor): a polygon's chain end
    // moving on to the next corner keeps it.
    const bool cut = segmentCutsPolygon(a, b, p.world);
    p.segmentDepths.push_back({wa.pulley, wb.pulley, left, right, cut});
    if ((!onPath && i == host) || join >= 0 || p.dropped || firstUpdate_ || !cut) continue;
    const auto was = std::find_if(before.begin(), before.end(), [&](const auto& d) {
      return d.from == wa.pulley && d.to == wb.pulley;
    });
    if (was == before.end() || was->cut) continue;
    // A point fixed in the world inside the hull: no taut path round it (joinRound).
    if ((wa.body < 0 && insideConvex(a, p.world)) || (wb.body < 0 && insideConvex(b, p.world)))
      continue;
    // It wraps on the side it came from, whichever it was first wrapped on: a body never passes
    // through the rope (docs/knocks.md, "Flung past a neighbour"). It lay wholly on one side of
    // the segment's line at the last update; lying across it (beyond an end: a spinning polygon
    // coming down on a bend of the rope), it joins on the side the segment barely bends round.
    const bool oneSide = was->left <= 0 || was->right <= 0;
    WrapSide side = was->right <= 0 ? WrapSide::Right : WrapSide::Left;
    if (!oneSide) {
      if (onPath) continue;
      const double viaLeft = crossedJoinDetour(a, b, p.world, WrapSide::Left);
      const double viaRight = crossedJoinDetour(a, b, p.world, WrapSide::Right);
      side = viaLeft <= viaRight ? WrapSide::Left : WrapSide::Right;
      if (std::min(viaLeft, viaRight) > kCrossedJoinDetour) continue;
    }
    // Off the path, it joins where the World located the crossing (on the old path); one it
    // crossed while on the path elsewhere may lie deep across the segment by now.
    if (oneSide && !onPath && crossedJoinDetour(a, b, p.world, side) > kLengthJump) continue;
    if (onPath) {
      if (own < 0) own = ownWrapDetour(path_, j);
      const double detour = crossedJoinDetour(a, b, p.world, side);
      // Wedged between two strands, moving would leave its old place's straightened rope across
      // it: its second place joins there instead, and the rope bends round it at both, whatever
      // lies between them and however deep its own wrap (a point's bend with the polygon inside
      // it is a hairpin over the point; docs/knocks.md, "Wedged in its neighbour's loop"). So
      // does one whose own wrap keeps it at its place (it cannot move) where it crosses the other
      // strand of the fixed point its own place runs to: swung over the point into the other
      // loop, the rope went through it there.
      const bool moves =
          std::abs(detour - own) <= kCrossedJoinDetour && neighboursKept(i, side, true);
      const bool wedged = segmentCutsPolygon(oldFrom, oldTo, p.world);
      // At a fixed point's bend: its own place runs into (or out of) a point pulley fixed in the
      // world, and the segment it crosses is that point's other strand (docs/knocks.md, "Across
      // the other strand at a point").
      auto fixedPoint = [](const WrapPoint& w) {
        return w.kind == WrapPoint::Kind::Point && w.body < 0;
      };
      const bool atPointsBend =
          (fixedPoint(wa) && i >= 1 && path_[i - 1].pulley == j) ||
          (fixedPoint(wb) && i + 2 < path_.size() && path_[i + 2].pulley == j);
      // Or the strand it crosses runs from the place next to its own along the path (past that
      // place's chain) to a point fixed in the world (an end anchor, a point pulley), its own place
      // wound less than a whole turn: swung round its neighbour, it came down on that neighbour's
      // strand (docs/knocks.md, "Across a strand to a fixed point"). Wound a turn or more, a
      // second place there tangled the two (releases jumped the length 2-9 cm); on a strand from
      // a place not next to its own, two squares wound round each other and fell through the rope.
      auto fixedEnd = [](const WrapPoint& w) {
        return w.body < 0 &&
               (w.kind == WrapPoint::Kind::Anchor || w.kind == WrapPoint::Kind::Point);
      };
      // Pulley j's place is next to the segment's end at path_[k] (past that place's chain),
      // on the side away from the segment.
      auto placeBeyond = [&](size_t k, int walk) {
        if (path_[k].kind != WrapPoint::Kind::Vertex) return false;
        const int n = static_cast<int>(path_.size());
        int m = static_cast<int>(k);
        while (m + walk >= 0 && m + walk < n && path_[m + walk].pulley == path_[k].pulley)
          m += walk;
        return m + walk >= 0 && m + walk < n && path_[m + walk].pulley == j;
      };
      const bool besideToFixed = p.arc < 2 * M_PI && ((fixedEnd(wa) && placeBeyond(i + 1, 1)) ||
                                                      (fixedEnd(wb) && placeBeyond(i, -1)));
      if (first > 0 && p.twin >= 0 && !pulleys_[p.twin].engaged && detour <= kCrossedJoinDetour &&
          (wedged || (!moves && (atPointsBend || besideToFixed))) &&
          neighboursKept(i, side, false)) {
        join = static_cast<int>(i);
        joinSide = side;
        joining = p.twin;
        continue;
      }
      if (!moves) {
        // Still bending the rope at its place: while it lies barely across the segment, it
        // keeps the side it came from, and moves once its own wrap lets go.
        if (detour <= kCrossedJoinDetour) p.segmentDepths.back() = *was;
        continue;
      }
    }
    join = static_cast<int>(i);
    joinSide = side;
  }
  if (join < 0) return false;
  // Its place (or its second place): right after the pulley the segment starts at (first, after
  // the start anchor).
  placeAfterSegment(joining, static_cast<size_t>(join));
  PulleyState& q = pulleys_[joining];
  q.side = joinSide;
  q.engaged = true;
  q.dropped = false;
  q.hold = ChainHold{};
  q.arc = 0;
  q.segmentDepths.clear();
  return true;
}

}  // namespace cablelab
