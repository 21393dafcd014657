// The order in which the path meets its pulleys (docs/knocks.md, "Flung past a neighbour").
//
// A disengaged pulley joins the segment between its engaged neighbours in the scene's order. Two
// free polygons riding in one rope's loops knock and sling each other about: a polygon that left
// the rope came down on another segment of it (past its neighbour, on its neighbour's corner),
// which its place in the order never let it join, and the rope went through it. A free polygon
// (one-sided, on a moving body, not gripping, not tied) joins any segment it crosses from
// its non-wrap side, on the old path as at its own (the World locates the crossing), and takes
// its place in the order there. Off the path its place changes neither the length nor J.
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

bool Cable::joinOtherSegment(int j, size_t host) {
  PulleyState& p = pulleys_[j];
  std::vector<PulleyState::SegmentDepth> before;
  std::swap(before, p.segmentDepths);
  p.segmentDepths.clear();
  int join = -1;
  for (size_t i = 0; i + 1 < path_.size(); ++i) {
    if (chainEdge(i)) continue;
    const WrapPoint &wa = path_[i], &wb = path_[i + 1];
    const Vec2 a = wa.radius == 0 ? wa.world : wa.tangentOut;
    const Vec2 b = wb.radius == 0 ? wb.world : wb.tangentIn;
    double depth = -1e300;
    for (const Vec2& v : p.world) depth = std::max(depth, wrapSideDistance(a, b, v, p.side));
    // A segment is named by the pulleys at its ends (-1: an anchor): a polygon's chain end
    // moving on to the next corner keeps it.
    p.segmentDepths.push_back({wa.pulley, wb.pulley, depth});
    if (i == host || join >= 0 || p.dropped || firstUpdate_) continue;
    const auto was = std::find_if(before.begin(), before.end(), [&](const auto& d) {
      return d.from == wa.pulley && d.to == wb.pulley;
    });
    if (was == before.end() || was->depth > 0 || !segmentCutsPolygon(a, b, p.world)) continue;
    // A point fixed in the world inside the hull: no taut path round it (joinRound).
    if ((wa.body < 0 && insideConvex(a, p.world)) || (wb.body < 0 && insideConvex(b, p.world)))
      continue;
    join = static_cast<int>(i);
  }
  if (join < 0) return false;
  // Its place: right after the pulley the segment starts at (first, after the start anchor).
  order_.erase(order_.begin() + rank_[j]);
  const int after = path_[join].pulley;
  order_.insert(after < 0 ? order_.begin() : std::find(order_.begin(), order_.end(), after) + 1, j);
  for (size_t r = 0; r < order_.size(); ++r) rank_[order_[r]] = static_cast<int>(r);
  p.engaged = true;
  p.hold = ChainHold{};
  p.arc = 0;
  p.segmentDepths.clear();
  return true;
}

}  // namespace cablelab
