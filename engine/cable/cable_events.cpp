// The next wrap change of a cable inside a sub-step (docs/cables.md, "Events").
//
// Every change of the wrap set is a sign change of one signed distance along the sub-step's
// motion: a disengaged pulley's point (or a polygon vertex) crossing the segment it would sit on,
// a polygon's next vertex crossing the segment leaving its chain, or the turn at a wrap point
// straightening. Located in time, the change can be made where the new point lies on the old
// path, which is what theorem 1 needs for the velocities not to jump.
#include <algorithm>
#include <cmath>

#include "engine/cable/body_frames.h"
#include "engine/cable/cable.h"
#include "engine/cable/crossing.h"
#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

// A point moving with its body from the start pose (`frames` holds the start rotations).
MovingPoint startPoint(std::span<const BodyState> motion, BodyFrames& frames, int body,
                       const Vec2& local) {
  if (body < 0) return MovingPoint::on(motion, body, local);
  const BodyFrames::Rotation& r = frames.rotation(body);
  return MovingPoint::on(motion, body, local, r.c, r.s);
}

void keepEarliest(std::optional<WrapEvent>& best, double time, int pulley, WrapEvent::Kind kind,
                  int vertex) {
  if (!best || time < best->time) best = WrapEvent{time, pulley, kind, vertex};
}

}  // namespace

int Cable::chainEndNeighbour(const WrapPoint& end, bool entering) const {
  const PulleyState& p = pulleys_[end.pulley];
  const int n = static_cast<int>(p.local.size());
  const int walk = p.side == WrapSide::Right ? 1 : -1;
  return ((entering ? end.vertex - walk : end.vertex + walk) % n + n) % n;
}

std::optional<WrapEvent> Cable::nextEvent(std::span<const BodyState> motion, double h) const {
  if (path_.size() < 2) return std::nullopt;
  // No watched distance can reach zero over the sub-step (wrap_skip.cpp).
  if (skipping_ && skipValid_ && wrapSetCertain(motion, h)) {
    ++skippedSearches_;
    return std::nullopt;
  }
  return searchEvents(motion, h);
}

// Apart from nextEvent(), whose skipped calls (most of them) then set up none of this.
std::optional<WrapEvent> Cable::searchEvents(std::span<const BodyState> motion, double h) const {
  std::optional<WrapEvent> best;
  const int count = static_cast<int>(pulleys_.size());
  BodyFrames frames(motion);
  auto moving = [&](const WrapPoint& w) { return startPoint(motion, frames, w.body, w.local); };
  // Where the cable touches a path point: a circle's tangent point (fixed on its body for the
  // sub-step, a first-order guess), else the point itself.
  auto contact = [&](const WrapPoint& w, const Vec2& world) {
    if (w.kind != WrapPoint::Kind::Circle) return moving(w);
    if (w.body < 0) return MovingPoint::on(motion, -1, world);
    return startPoint(motion, frames, w.body, frames.localPoint(w.body, world));
  };

  // Joins: a point that would enter the path between path_[i] and path_[i + 1].
  for (size_t i = 0; i + 1 < path_.size(); ++i) {
    const WrapPoint& a = path_[i];
    const WrapPoint& b = path_[i + 1];
    const MovingPoint ma = contact(a, a.tangentOut), mb = contact(b, b.tangentIn);
    // A circle joins when it comes within its radius of the segment; an auto pulley, or a free
    // polygon joining a segment not its own (pulley_order.cpp), from either side.
    auto tryPoint = [&](int j, int vertex, WrapEvent::Kind kind, bool elsewhere = false) {
      const PulleyState& p = pulleys_[j];
      const MovingPoint mp = startPoint(motion, frames, p.body, p.local[vertex]);
      const double reach = p.circle ? p.radius : 0.0;
      for (const WrapSide side : {WrapSide::Left, WrapSide::Right}) {
        if (!p.autoSide && !elsewhere && side != p.side) continue;
        const double horizon = best ? best->time : h;
        if (auto c = pointCrossesSegment(ma, mb, mp, side, horizon, reach))
          keepEarliest(best, c->time, j, kind, p.polygon ? vertex : -1);
      }
    };
    // Disengaged pulleys ordered between the segment's ends (places in the path's order).
    const int lo = a.pulley < 0 ? -1 : rank_[a.pulley];  // -1 at the start anchor
    const int hi = b.pulley < 0 ? count : rank_[b.pulley];
    for (int r = lo + 1; r < hi; ++r) {
      const int j = order_[r];
      const PulleyState& p = pulleys_[j];
      if (p.engaged || p.side == WrapSide::Threaded || p.secondPlace ||
          besideItsOtherPlace(j, a, b))
        continue;
      for (int v = 0; v < static_cast<int>(p.local.size()); ++v)
        tryPoint(j, v, WrapEvent::Kind::Join);
    }
    // Free polygons placed elsewhere join any segment they cross, and one on the path may move
    // its place to a segment not its own (pulley_order.cpp).
    if (!chainEdge(i))
      for (int r = 0; r < count; ++r) {
        const int j = order_[r];
        const PulleyState& p = pulleys_[j];
        const bool mine = a.pulley == j || b.pulley == j ||
                          (p.twin >= 0 && (a.pulley == p.twin || b.pulley == p.twin));
        const bool own = p.engaged ? mine : r > lo && r < hi;
        if (own || p.dropped || idleSecondPlace(j) || !joinsAnySegment(j) ||
            besideItsOtherPlace(j, a, b))
          continue;
        // One on the path that the segment already cuts cannot move there (pulley_order.cpp).
        if (p.engaged && segmentCutsPolygon(a.leaving(), b.arriving(), p.world)) continue;
        for (int v = 0; v < static_cast<int>(pulleys_[j].local.size()); ++v)
          tryPoint(j, v, WrapEvent::Kind::Join, true);
      }
    // A point fixed in the world at an end of the segment going into or out of a moving polygon's
    // hull (across edge k): a polygon off the path must not join round it then, and one on it
    // holds its chain end there (docs/cables.md, "Points inside a hull"). A fast hull can take
    // the point in and out within one step, and the next update would walk the polygon afresh,
    // off the old path.
    // A neighbouring polygon's corner (`corner`) is watched the same way: it holds the chain end
    // too (holdsAgainst), and found inside at the next update it had crossed the end's next edge
    // unseen, the chain then rebuilt off the old path (docs/knocks.md, "A neighbour's corner
    // entering the hull").
    auto tryHull = [&](int j, const WrapPoint& terminal, bool corner = false) {
      const PulleyState& p = pulleys_[j];
      if (!p.polygon || p.body < 0 || p.tiedEnd != 0 || terminal.radius != 0 ||
          (terminal.body >= 0 && (!corner || terminal.body == p.body)))
        return;
      // Most steps the hull stays farther from the point than its farthest vertex from the body's
      // origin, which moves on a straight line over the sub-step: nothing to search. A corner
      // moves with its body: its velocity now, and at most its turn's arc off that line.
      const BodyState& body = motion[p.body];
      Vec2 pointVelocity = Vec2::Zero();
      double reach = 0;
      if (terminal.body >= 0) {
        const BodyState& other = motion[terminal.body];
        const Vec2 arm = terminal.world - other.position;
        pointVelocity = other.velocity + other.angularVelocity * Vec2(-arm.y(), arm.x());
        reach += std::abs(other.angularVelocity) * arm.norm() * h;
      }
      const Vec2 relative = body.velocity - pointVelocity;
      const double horizon = best ? best->time : h, speed2 = relative.squaredNorm();
      const Vec2 away = body.position - terminal.world;
      const double closest =
          speed2 > 0 ? std::clamp(-away.dot(relative) / speed2, 0.0, horizon) : 0.0;
      double farthest = 0;
      for (const Vec2& v : p.local) farthest = std::max(farthest, v.norm());
      reach += farthest;
      if ((away + closest * relative).norm() > reach) return;
      const MovingPoint point = terminal.body < 0
                                    ? MovingPoint::on(motion, -1, terminal.world)
                                    : startPoint(motion, frames, terminal.body, terminal.local);
      const int n = static_cast<int>(p.local.size());
      for (int k = 0; k < n; ++k) {
        const MovingPoint from = startPoint(motion, frames, p.body, p.local[k]);
        const MovingPoint to = startPoint(motion, frames, p.body, p.local[(k + 1) % n]);
        for (const WrapSide side : {WrapSide::Left, WrapSide::Right})
          if (auto c = pointCrossesSegment(from, to, point, side, best ? best->time : h))
            keepEarliest(best, c->time, j, WrapEvent::Kind::Hull, k);
      }
    };
    for (int r = lo + 1; r < hi; ++r)
      if (const int j = order_[r]; !pulleys_[j].engaged && pulleys_[j].side != WrapSide::Threaded &&
                                   !pulleys_[j].secondPlace)
        for (const WrapPoint* terminal : {&a, &b}) tryHull(j, *terminal);
    if (a.kind == WrapPoint::Kind::Vertex && b.kind != WrapPoint::Kind::Vertex)
      tryHull(a.pulley, b);
    if (b.kind == WrapPoint::Kind::Vertex && a.kind != WrapPoint::Kind::Vertex)
      tryHull(b.pulley, a);
    if (a.kind == WrapPoint::Kind::Vertex && b.kind == WrapPoint::Kind::Vertex &&
        a.body != b.body) {
      tryHull(a.pulley, b, true);
      tryHull(b.pulley, a, true);
    }
    // A polygon's chain grows at its ends: the vertex before its first one (walking round it
    // with the polygon on the cable's right) against the segment entering it, the one after its
    // last against the segment leaving it. On a convex polygon no other vertex can reach those
    // segments first, and that vertex may be in the chain already (a wrap of a whole turn).
    int tied;  // a polygon the cable is tied to joins the segment into its end at its corner
    if (const int corner = tiedCornerWaiting(i, tied); corner >= 0)
      tryPoint(tied, corner, WrapEvent::Kind::Vertex);
    if (a.kind == WrapPoint::Kind::Vertex && b.kind == WrapPoint::Kind::Vertex &&
        a.pulley == b.pulley)
      continue;  // an edge of the chain: the convex polygon stays on its inner side
    for (const WrapPoint* end : {&a, &b}) {
      if (end->kind != WrapPoint::Kind::Vertex) continue;
      const PulleyState& p = pulleys_[end->pulley];
      // The edge into a tied end: the next vertex is the end's or beyond it on the same line.
      // Only that edge: the free part of the cable still winds on at the chain's other end.
      if (end == &a ? p.tiedEnd > 0 && i + 2 == path_.size() : p.tiedEnd < 0 && i == 0) continue;
      // A held end takes no vertex while its terminal is in the hull or the rope doubles back
      // round it (wrapChainHeld): an event there would cut the step for no change.
      const bool into = end == &a;
      const WrapPoint& terminal = into ? b : a;
      if ((into ? p.hold.holdingInto : p.hold.holdingFrom) &&
          ((into ? p.hold.turnInto : p.hold.turnFrom) >= M_PI ||
           insideConvex(terminal.world, p.world)))
        continue;
      const int v = chainEndNeighbour(*end, end == &b);
      tryPoint(end->pulley, v, WrapEvent::Kind::Vertex);
    }
  }
  // Leaves: the turn at a wrap point straightens.
  for (size_t i = 1; i + 1 < path_.size(); ++i) {
    const WrapPoint& w = path_[i];
    if (pulleys_[w.pulley].side == WrapSide::Threaded) continue;
    const double horizon = best ? best->time : h;
    // A circle leaves when its arc reaches 0; the straight-line test below sees that only on
    // the last turn (wound further, the line between the neighbours says nothing).
    if (w.kind == WrapPoint::Kind::Circle && w.arc > M_PI) continue;
    const double reach = w.kind == WrapPoint::Kind::Circle ? std::abs(w.radius) : 0.0;
    if (auto t = turnStraightens(contact(path_[i - 1], path_[i - 1].tangentOut), moving(w),
                                 contact(path_[i + 1], path_[i + 1].tangentIn),
                                 pulleys_[w.pulley].side, horizon, reach))
      keepEarliest(
          best, *t, w.pulley,
          w.kind == WrapPoint::Kind::Vertex ? WrapEvent::Kind::Vertex : WrapEvent::Kind::Leave,
          w.vertex);
  }
  return best;
}

}  // namespace cablelab
