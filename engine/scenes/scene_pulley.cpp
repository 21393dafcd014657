// Two boxes hung over two ground pulleys by one cable: the set-up of Box2D's pulley joint test
// (y = 16, L = 12, boxes 2 x 4), with ratio 1, so it can be run beside b2PulleyJoint.
#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makePulleyScene(const SceneParams& p) {
  const double y = 16, L = p.at("L"), a = 1, b = 2;
  SceneDef s;
  s.name = "pulley";
  s.description = "two bodies hung over two ground pulleys by one cable";
  s.view = {Vec2(0, y + 0.5 * L), L + 2 * b + 14};

  ShapeDef box;
  box.kind = ShapeDef::Kind::Polygon;
  box.vertices = {Vec2(-a, -b), Vec2(a, -b), Vec2(a, b), Vec2(-a, b)};
  BodyDef left, right;
  left.name = "left";
  left.position = Vec2(-10, y);
  left.mass = p.at("m_left");
  left.shapes = {box};
  right.name = "right";
  right.position = Vec2(10, y);
  right.mass = p.at("m_right");
  right.shapes = {box};
  s.bodies = {left, right};

  CableDef cable;
  cable.name = "cable";
  cable.start = {"left", Vec2(0, b)};
  PulleyDef p1, p2;
  p1.point = Vec2(-10, y + b + L);
  p1.side = WrapSide::Threaded;
  p2.point = Vec2(10, y + b + L);
  p2.side = WrapSide::Threaded;
  cable.pulleys = {p1, p2};
  cable.end = {"right", Vec2(0, b)};
  s.cables = {cable};
  return s;
}

}  // namespace cablelab
