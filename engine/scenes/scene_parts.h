// Bodies the built-in scenes share: a square weight and a wheel (a disc the cable touches, not
// the boxes). Private to engine/scenes.
#pragma once

#include <string>

#include "engine/model/scene.h"

namespace cablelab {

/// A square box of half side `half` (m) and mass `mass` (kg) at `position`.
inline BodyDef boxBody(const std::string& name, const Vec2& position, double mass, double half) {
  ShapeDef box;
  box.kind = ShapeDef::Kind::Polygon;
  box.vertices = {Vec2(-half, -half), Vec2(half, -half), Vec2(half, half), Vec2(-half, half)};
  BodyDef b;
  b.name = name;
  b.position = position;
  b.mass = mass;
  b.shapes = {box};
  return b;
}

/// A disc of radius `radius` (m) at `position`, a sensor: the cable wraps it, bodies pass it.
inline BodyDef wheelBody(const std::string& name, const Vec2& position, double radius) {
  ShapeDef disc;
  disc.radius = radius;
  disc.sensor = true;
  BodyDef b;
  b.name = name;
  b.position = position;
  b.shapes = {disc};
  return b;
}

}  // namespace cablelab
