#include "engine/dynamics/hull_contacts.h"

#include <algorithm>

#include "engine/cable/tied_end.h"
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

bool sameHullPair(const HullContact& a, const HullContact& b) {
  const bool polygons = !a.otherPolygon.empty() && !b.otherPolygon.empty();
  if (polygons)
    return (a.body == b.body && a.otherBody == b.otherBody) ||
           (a.body == b.otherBody && a.otherBody == b.body);
  return a.otherPolygon.empty() && b.otherPolygon.empty() && a.body == b.body &&
         a.otherBody == b.otherBody && a.point == b.point;
}

// Whether the disc of `radius` round `centre` meets convex counter-clockwise `hull`.
bool discMeetsHull(const Vec2& centre, double radius, const std::vector<Vec2>& hull) {
  if (insideConvex(centre, hull)) return true;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Vec2 a = hull[i], edge = hull[(i + 1) % hull.size()] - a;
    const double along = std::clamp((centre - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    if ((a + along * edge - centre).norm() <= radius) return true;
  }
  return false;
}

// Whether a shape of body `body` meets `hull` (world frame) in the scene's pose.
bool bodyMeetsHull(const SceneDef& scene, int body, const std::vector<Vec2>& hull) {
  const BodyDef& b = scene.bodies[body];
  for (const ShapeDef& shape : b.shapes) {
    const bool meets =
        shape.kind == ShapeDef::Kind::Circle
            ? discMeetsHull(placedInScene(scene, body, {shape.center})[0], shape.radius, hull)
            : hullsOverlap(hull, placedInScene(scene, body, shape.vertices));
    if (meets) return true;
  }
  return false;
}

// A polygon pulley held still (on the world, a static or a kinematic body) touches every point of
// its cable on a moving body: a bob the rope winds up onto it stops at its corner and rides round
// instead of passing into the hull, sensor or not (docs/cables.md, "Points inside a hull"). The
// knock is Box2D's, inelastic.
template <typename Moving, typename Add>
void addHeldStill(int body, const std::vector<Vec2>& polygon,
                  const std::vector<std::pair<int, Vec2>>& points, const Moving& moving,
                  const Add& add) {
  for (const auto& [pointBody, point] : points) {
    if (!moving(pointBody)) continue;
    HullContact pair;
    pair.body = body;
    pair.polygon = polygon;
    pair.otherBody = pointBody;
    pair.point = point;
    add(std::move(pair));
  }
}

}  // namespace

bool hullsOverlap(const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
  return !separatedByAnEdgeOf(p, q) && !separatedByAnEdgeOf(q, p);
}

std::vector<KnockResponse> knockResponses(const SceneDef& scene) {
  std::vector<KnockResponse> out(scene.bodies.size());
  std::vector<int> joints(scene.bodies.size(), 0);
  for (const JointDef& jd : scene.joints) {
    const int a = findBodyIndex(scene, jd.bodyA), b = findBodyIndex(scene, jd.bodyB);
    for (const int body : {a, b})
      if (body >= 0) ++joints[body];
    // A pivot: the body turns about a world point (no limit: the joint never pushes back).
    const int body = a < 0 ? b : (b < 0 ? a : -1);
    if (body < 0 || jd.kind != JointDef::Kind::Revolute || jd.enableLimit) continue;
    const BodyDef& bd = scene.bodies[body];
    out[body].pivoted = true;
    out[body].pivot = rotate(Vec2(jd.anchor - bd.position), -bd.angle);
  }
  for (size_t b = 0; b < joints.size(); ++b)
    out[b].known = joints[b] == 0 || (joints[b] == 1 && out[b].pivoted);
  return out;
}

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
    // A point on a moving body whose shapes meet the hull: the bodies pass through each other
    // by design (the hand's box between its fingers).
    if (c.otherPolygon.empty() && c.otherBody >= 0 && bodyMeetsHull(scene, c.otherBody, hull))
      return;
    c.apartFirst = c.otherPolygon.empty()
                       ? insideConvex(placedInScene(scene, c.otherBody, {c.point})[0], hull)
                       : hullsOverlap(hull, placedInScene(scene, c.otherBody, c.otherPolygon));
    for (const HullContact& d : out)
      if (sameHullPair(c, d)) return;
    out.push_back(std::move(c));
  };
  for (const CableDef& cable : scene.cables) {
    // The cable's points: its anchors (not drums) and point pulleys, each on its body (-1: the
    // world), a shapeless body's left out.
    std::vector<std::pair<int, Vec2>> points;
    for (const AnchorDef* anchor : {&cable.start, &cable.end})
      if (const int body = findBodyIndex(scene, anchor->body); anchor->radius == 0 && solid(body))
        points.emplace_back(body, anchor->point);
    for (const PulleyDef& pd : cable.pulleys)
      if (const int body = findBodyIndex(scene, pd.body);
          pd.kind == PulleyDef::Kind::Point && solid(body))
        points.emplace_back(body, pd.point);
    const int count = static_cast<int>(cable.pulleys.size());
    for (int j = 0; j < count; ++j) {
      const PulleyDef& pd = cable.pulleys[j];
      const int body = findBodyIndex(scene, pd.body);
      if (pd.kind != PulleyDef::Kind::Polygon) continue;
      if (!moving(body)) {
        addHeldStill(body, pulleyPolygon(scene, pd), points, moving, add);
        continue;
      }
      HullContact c;
      c.body = body;
      c.polygon = pulleyPolygon(scene, pd);
      // A spool: a cable end next to it is tied on its body, on or in its hull (tied_end.h; the
      // side only picks the corner).
      auto tiedOn = [&](const AnchorDef& end) {
        bool inside = false;
        return findBodyIndex(scene, end.body) == body && end.radius == 0 &&
               tiedEndCorner(end.point, c.polygon, pd.side, inside) >= 0;
      };
      const bool spool = (j == 0 && tiedOn(cable.start)) || (j == count - 1 && tiedOn(cable.end));
      for (const auto& [pointBody, point] : points) {
        // A point on another moving body touches a spool (wound right up to it, the rope pulls it
        // there) and a free pulley of a rigid rope, whose catch is inelastic as Box2D's knock is.
        // An elastic rope keeps its energy: its point bounces off a free pulley (hull_bounce.h;
        // docs/cables.md, "Points inside a hull"), a point fixed in the world too. Box2D's contact
        // took a loop's polygon's whole approach at its anchor and, touching, handed its step to
        // the main solve's damped spring: 9-50% of its energy in a minute.
        if (pointBody == body) continue;
        HullContact pair = c;
        pair.otherBody = pointBody;
        pair.point = point;
        pair.bounces = !spool && cable.stiffness > 0;
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
