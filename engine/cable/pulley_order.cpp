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
// length nor J.
#include <algorithm>
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

bool Cable::joinCrossedSegment(int j) {
  PulleyState& p = pulleys_[j];
  std::vector<PulleyState::SegmentDepth> before;
  std::swap(before, p.segmentDepths);
  p.segmentDepths.clear();
  int join = -1;
  WrapSide joinSide = p.side;
  // Its own segment (from the path point before it in the order) is joinRound's.
  size_t host = 0;
  while (host + 2 < path_.size() && rank_[path_[host + 1].pulley] < rank_[j]) ++host;
  for (size_t i = 0; i + 1 < path_.size(); ++i) {
    if (chainEdge(i)) continue;
    const WrapPoint &wa = path_[i], &wb = path_[i + 1];
    const Vec2 a = wa.radius == 0 ? wa.world : wa.tangentOut;
    const Vec2 b = wb.radius == 0 ? wb.world : wb.tangentIn;
    double left = -1e300, right = -1e300;
    for (const Vec2& v : p.world) {
      left = std::max(left, wrapSideDistance(a, b, v, WrapSide::Left));
      right = std::max(right, wrapSideDistance(a, b, v, WrapSide::Right));
    }
    // A segment is named by the pulleys at its ends (-1: an anchor): a polygon's chain end
    // moving on to the next corner keeps it.
    const bool cut = segmentCutsPolygon(a, b, p.world);
    p.segmentDepths.push_back({wa.pulley, wb.pulley, left, right, cut});
    if (i == host || join >= 0 || p.dropped || firstUpdate_ || !cut) continue;
    const auto was = std::find_if(before.begin(), before.end(), [&](const auto& d) {
      return d.from == wa.pulley && d.to == wb.pulley;
    });
    // It wraps on the side it came from, whichever it was first wrapped on: a body never passes
    // through the rope (docs/knocks.md, "Flung past a neighbour"). It lay wholly on one side of
    // the segment's line at the last update (lying across it, it may have come round an end).
    if (was == before.end() || was->cut || (was->left > 0 && was->right > 0)) continue;
    // A point fixed in the world inside the hull: no taut path round it (joinRound).
    if ((wa.body < 0 && insideConvex(a, p.world)) || (wb.body < 0 && insideConvex(b, p.world)))
      continue;
    join = static_cast<int>(i);
    joinSide = was->right <= 0 ? WrapSide::Right : WrapSide::Left;
  }
  if (join < 0) return false;
  // Its place: right after the pulley the segment starts at (first, after the start anchor).
  order_.erase(order_.begin() + rank_[j]);
  const int after = path_[join].pulley;
  order_.insert(after < 0 ? order_.begin() : std::find(order_.begin(), order_.end(), after) + 1, j);
  for (size_t r = 0; r < order_.size(); ++r) rank_[order_[r]] = static_cast<int>(r);
  p.side = joinSide;
  p.engaged = true;
  p.hold = ChainHold{};
  p.arc = 0;
  p.segmentDepths.clear();
  return true;
}

}  // namespace cablelab
