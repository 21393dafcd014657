#include "engine/dynamics/hull_bounce.h"

#include <algorithm>
#include <limits>

namespace cablelab {

namespace {

// The point of convex counter-clockwise `hull` nearest to `p`, or nothing if `p` is inside.
bool nearestOnHullFromOutside(const Vec2& p, const std::vector<Vec2>& hull, Vec2& nearest) {
  bool outside = false;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < hull.size(); ++i) {
    const Vec2 a = hull[i], edge = hull[(i + 1) % hull.size()] - a;
    outside |= cross(edge, p - a) < 0;
    const double along = std::clamp((p - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    const Vec2 q = a + along * edge;
    if ((p - q).squaredNorm() < best) {
      best = (p - q).squaredNorm();
      nearest = q;
    }
  }
  return outside && best > 0;
}

}  // namespace

HullBounce::HullBounce(const SceneDef& scene, const std::vector<HullContact>& contacts)
    : responses_(knockResponses(scene)) {
  for (const HullContact& c : contacts) {
    if (!c.bounces || !c.otherPolygon.empty()) continue;
    if (!responses_[c.body].known || (c.otherBody >= 0 && !responses_[c.otherBody].known)) continue;
    pairs_.push_back({c.body, c.otherBody, c.polygon, c.point, false});
  }
}

double HullBounce::inverseMass(const BodyState& b, int body, const Vec2& at,
                               const Vec2& normal) const {
  if (body < 0) return 0;  // a point fixed in the world
  const KnockResponse& r = responses_[body];
  if (!r.pivoted) {
    const double arm = cross(Vec2(at - b.position), normal);
    return b.invMass + b.invInertia * arm * arm;
  }
  if (!(b.invMass > 0) || !(b.invInertia > 0)) return 0;  // held still by its pivot
  const double arm = cross(Vec2(at - pivotOf(b, r)), normal);
  return inversePivotInertia(b, r) * arm * arm;
}

Vec2 HullBounce::pivotOf(const BodyState& b, const KnockResponse& r) {
  return b.position + rotate(r.pivot, b.angle);
}

// The parallel-axis theorem: the moment about the pivot is I + m d^2.
double HullBounce::inversePivotInertia(const BodyState& b, const KnockResponse& r) {
  return 1 / (1 / b.invInertia + r.pivot.squaredNorm() / b.invMass);
}

void HullBounce::applyImpulse(BodyState& b, int body, const Vec2& at, const Vec2& impulse) const {
  if (body < 0) return;
  const KnockResponse& r = responses_[body];
  if (!r.pivoted) {
    b.velocity += b.invMass * impulse;
    b.angularVelocity += b.invInertia * cross(Vec2(at - b.position), impulse);
    return;
  }
  if (!(b.invMass > 0) || !(b.invInertia > 0)) return;
  const Vec2 pivot = pivotOf(b, r);
  const double turn = inversePivotInertia(b, r) * cross(Vec2(at - pivot), impulse);
  b.angularVelocity += turn;
  b.velocity += turn * perp(b.position - pivot);
}

std::vector<int> HullBounce::bounce(std::vector<BodyState>& bodies, double horizon, double skin) {
  std::vector<int> changed;
  // A bounce turns its bodies, which may bring another pair on them in: a few passes.
  constexpr int kPasses = 4;
  BodyState world;  // the world's points: at rest, no inverse mass
  for (int pass = 0; pass < kPasses; ++pass) {
    bool any = false;
    for (Pair& p : pairs_) {
      BodyState& polygonState = bodies[p.polygonBody];
      // A point fixed in the world (an anchor of the rope the free polygon rides in) holds still.
      BodyState& pointState = p.pointBody >= 0 ? bodies[p.pointBody] : world;
      hull_.clear();
      for (const Vec2& v : p.polygon)
        hull_.push_back(polygonState.position + rotate(v, polygonState.angle));
      const Vec2 point = pointState.position + rotate(p.point, pointState.angle);
      Vec2 nearest;
      if (!nearestOnHullFromOutside(point, hull_, nearest)) continue;
      const double gap = (point - nearest).norm();
      p.armed |= gap > skin;
      if (!p.armed) continue;
      const Vec2 normal = (point - nearest) / gap;  // out of the hull, towards the point
      const double approach =
          normal.dot(pointVelocity(pointState, point) - pointVelocity(polygonState, nearest));
      if (!(approach < 0) || gap + approach * horizon > skin) continue;
      const double w = inverseMass(pointState, p.pointBody, point, normal) +
                       inverseMass(polygonState, p.polygonBody, nearest, normal);
      if (!(w > 0)) continue;
      // -2 approach / w reverses the relative normal speed; its work is zero (docs/cables.md).
      const Vec2 impulse = (-2 * approach / w) * normal;
      applyImpulse(pointState, p.pointBody, point, impulse);
      applyImpulse(polygonState, p.polygonBody, nearest, -impulse);
      if (p.pointBody >= 0) changed.push_back(p.pointBody);
      changed.push_back(p.polygonBody);
      any = true;
    }
    if (!any) break;
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

}  // namespace cablelab
