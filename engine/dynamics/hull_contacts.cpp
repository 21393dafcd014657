#include "engine/dynamics/hull_contacts.h"

#include "engine/cable/wrap.h"

namespace cablelab {

namespace {

constexpr size_t kMostHullVertices = 8;  // Box2D's b2_maxPolygonVertices

// `local` placed at body `body`'s pose in the scene (the world's frame for -1).
std::vector<Vec2> placedInScene(const SceneDef& scene, int body, const std::vector<Vec2>& local) {
  if (body < 0) return local;
  const BodyDef& b = scene.bodies[body];
  std::vector<Vec2> out;
  for (const Vec2& v : local) out.push_back(b.position + rotate(v, b.angle));
  return out;
}

// Whether convex counter-clockwise `q` lies wholly outside one edge of convex `p`.
bool separatedByAnEdgeOf(const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2 edge = p[(i + 1) % p.size()] - p[i];
    bool outside = true;
    for (const Vec2& v : q) outside &= cross(edge, v - p[i]) < 0;
    if (outside) return true;
  }
  return false;
}

bool hullsOverlap(const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
  return !separatedByAnEdgeOf(p, q) && !separatedByAnEdgeOf(q, p);
}

bool sameHullPair(const HullContact& a, const HullContact& b) {
  const bool polygons = !a.otherPolygon.empty() && !b.otherPolygon.empty();
  if (polygons)
    return (a.body == b.body && a.otherBody == b.otherBody) ||
           (a.body == b.otherBody && a.otherBody == b.body);
  return a.otherPolygon.empty() && b.otherPolygon.empty() && a.body == b.body && a.point == b.point;
}

}  // namespace

std::vector<HullContact> hullContacts(const SceneDef& scene) {
  std::vector<HullContact> out;
  // A shapeless body is a point mass: its pulley's polygon guides the rope and touches nothing.
  auto solid = [&](int body) { return body < 0 || !scene.bodies[body].shapes.empty(); };
  auto moving = [&](int body) {
    return body >= 0 && scene.bodies[body].type == BodyType::Dynamic && solid(body);
  };
  auto add = [&](HullContact c) {
    if (c.polygon.size() > kMostHullVertices || c.otherPolygon.size() > kMostHullVertices) return;
    const std::vector<Vec2> hull = placedInScene(scene, c.body, c.polygon);
    const bool overlapping =
        c.otherPolygon.empty()
            ? insideConvex(c.point, hull)
            : hullsOverlap(hull, placedInScene(scene, c.otherBody, c.otherPolygon));
    if (overlapping) return;
    for (const HullContact& d : out)
      if (sameHullPair(c, d)) return;
    out.push_back(std::move(c));
  };
  for (const CableDef& cable : scene.cables) {
    // The cable's points fixed in the world: its anchors and point pulleys there.
    std::vector<Vec2> points;
    for (const AnchorDef* anchor : {&cable.start, &cable.end})
      if (findBodyIndex(scene, anchor->body) == -1 && anchor->radius == 0)
        points.push_back(anchor->point);
    for (const PulleyDef& pd : cable.pulleys)
      if (pd.kind == PulleyDef::Kind::Point && findBodyIndex(scene, pd.body) == -1)
        points.push_back(pd.point);
    const int count = static_cast<int>(cable.pulleys.size());
    for (int j = 0; j < count; ++j) {
      const PulleyDef& pd = cable.pulleys[j];
      const int body = findBodyIndex(scene, pd.body);
      if (pd.kind != PulleyDef::Kind::Polygon || !moving(body)) continue;
      HullContact c;
      c.body = body;
      c.polygon = pulleyPolygon(scene, pd);
      for (const Vec2& p : points) {
        HullContact pair = c;
        pair.point = p;
        add(std::move(pair));
      }
      for (int k = 0; k < count; ++k) {
        const PulleyDef& other = cable.pulleys[k];
        HullContact pair = c;
        pair.otherBody = findBodyIndex(scene, other.body);
        if (k == j || other.kind != PulleyDef::Kind::Polygon || pair.otherBody == body ||
            !solid(pair.otherBody))
          continue;
        pair.otherPolygon = pulleyPolygon(scene, other);
        add(std::move(pair));
      }
    }
  }
  return out;
}

}  // namespace cablelab
