// Parts the tests' hand-built scenes share: a sensor box shape (nothing touches it) and a body
// pivoted on the world.
#pragma once

#include <string>

#include "engine/model/scene.h"

namespace cablelab::test {

/// A box of half sizes (hx, hy) about the body origin, a sensor.
inline ShapeDef sensorBox(double hx, double hy) {
  ShapeDef box;
  box.kind = ShapeDef::Kind::Polygon;
  box.vertices = {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)};
  box.sensor = true;
  return box;
}

/// A disc of `radius` about the body origin, a sensor.
inline ShapeDef sensorDisc(double radius) {
  ShapeDef disc;
  disc.kind = ShapeDef::Kind::Circle;
  disc.radius = radius;
  disc.sensor = true;
  return disc;
}

/// A revolute joint "pivot" from the world to `body` at the world point `anchor`.
inline JointDef worldPivot(const std::string& body, const Vec2& anchor) {
  JointDef pivot;
  pivot.name = "pivot";
  pivot.kind = JointDef::Kind::Revolute;
  pivot.bodyA = "world";
  pivot.bodyB = body;
  pivot.anchor = anchor;
  return pivot;
}

}  // namespace cablelab::test
