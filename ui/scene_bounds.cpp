#include "ui/scene_bounds.h"

#include <algorithm>

namespace cablelab::ui {
namespace {

Vec2 onBody(const World& world, int body, const Vec2& local) {
  if (body < 0) return local;
  const BodyState& s = world.body(body);
  return s.position + rotate(local, s.angle);
}

void includeShapes(WorldBounds& b, const World& world, int body, double margin) {
  for (const ShapeDef& shape : world.scene().bodies[body].shapes) {
    if (shape.kind == ShapeDef::Kind::Circle)
      b.include(onBody(world, body, shape.center), shape.radius + margin);
    for (const Vec2& v : shape.vertices) b.include(onBody(world, body, v), margin);
  }
}

}  // namespace

WorldBounds bodyBounds(const World& world, int body, double margin) {
  WorldBounds b;
  includeShapes(b, world, body, margin);
  return b;
}

WorldBounds sceneBounds(const World& world, double margin) {
  WorldBounds b;
  const SceneDef& scene = world.scene();
  for (int i = 0; i < world.bodyCount(); ++i)
    if (scene.bodies[i].type != BodyType::Static) includeShapes(b, world, i, margin);
  for (int i = 0; i < world.cableCount(); ++i)
    for (const WrapPoint& p : world.cable(i).path()) b.include(p.world, margin);
  for (const CableDef& c : scene.cables)
    for (const PulleyDef& p : c.pulleys) {
      const int body = findBodyIndex(scene, p.body);
      if (p.kind == PulleyDef::Kind::Polygon && p.vertices.empty() && body >= 0)
        includeShapes(b, world, body, margin);
      for (const Vec2& v : p.vertices) b.include(onBody(world, body, v), margin);
      if (p.kind != PulleyDef::Kind::Polygon)
        b.include(onBody(world, body, p.point), std::abs(p.radius) + margin);
    }
  // The fixed bodies, each cut to the reach of the moving parts (a wide ground's middle part).
  const WorldBounds moving = b;
  for (int i = 0; i < world.bodyCount(); ++i) {
    if (scene.bodies[i].type != BodyType::Static) continue;
    WorldBounds fixed = bodyBounds(world, i, margin);
    if (!moving.empty()) {
      const double reach = kFixedReach * (moving.hi - moving.lo).maxCoeff();
      fixed.lo = fixed.lo.cwiseMax(moving.lo - Vec2(reach, reach));
      fixed.hi = fixed.hi.cwiseMin(moving.hi + Vec2(reach, reach));
    }
    if (fixed.empty()) continue;  // far from the moving parts
    b.include(fixed.lo);
    b.include(fixed.hi);
  }
  return b;
}

LabelBox screenBox(const WorldBounds& bounds, const Camera& camera) {
  if (bounds.empty()) return {};
  const Vec2 a = camera.toScreen(bounds.lo), b = camera.toScreen(bounds.hi);
  return {std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.x(), b.x()),
          std::max(a.y(), b.y())};
}

}  // namespace cablelab::ui
