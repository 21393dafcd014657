// Block and tackle: two fixed sheaves above, a moving block with two sheaves below, the rope
// anchored at the top; four falls carry the block, so the effort lifts four times its weight
// (the effort moves four times as far). Every fall is vertical; the sheaves are frictionless.
#include <algorithm>

#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makeTackleScene(const SceneParams& p) {
  const double r = p.at("r"), top = 4.0, low = 2.0;
  SceneDef s;
  s.name = "tackle";
  s.description =
      "block and tackle, 4 falls: the effort lifts 4x its weight; try --set m_effort=1 "
      "(balance with m_load=4), m_effort=0.5 (the load sinks)";
  s.view = {Vec2(4 * r, 2.6), 4.0};

  ShapeDef box;
  box.kind = ShapeDef::Kind::Polygon;
  box.vertices = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1), Vec2(-0.1, 0.1)};
  BodyDef block;
  block.name = "block";
  block.position = Vec2(3 * r, low);
  block.mass = p.at("m_load");
  block.fixedRotation = true;
  ShapeDef plate;
  plate.kind = ShapeDef::Kind::Polygon;
  plate.sensor = true;
  // Under the sheaves, 0.3 m down or 0.15 m below them (a sheave of 0.3 m or more made the plate
  // a clockwise polygon, and the scene was refused).
  const double bottom = -std::max(0.3, r + 0.15);
  plate.vertices = {Vec2(-3 * r, bottom), Vec2(3 * r, bottom), Vec2(3 * r, -r), Vec2(-3 * r, -r)};
  block.shapes = {plate};
  BodyDef effort;
  effort.name = "effort";
  effort.position = Vec2(8 * r, low + 0.5);
  effort.mass = p.at("m_effort");
  effort.shapes = {box};
  s.bodies = {block, effort};

  auto sheave = [&](const std::string& body, const Vec2& centre, WrapSide side) {
    PulleyDef d;
    d.kind = PulleyDef::Kind::Circle;
    d.body = body;
    d.point = centre;
    d.radius = r;
    d.side = side;
    d.turns = 0.5;
    return d;
  };
  CableDef rope;
  rope.name = "rope";
  rope.start = {"world", Vec2(0, top)};
  // Down round the block's left sheave (counter-clockwise), up over the left fixed sheave
  // (clockwise), down round the right block sheave, up over the right fixed sheave, down.
  rope.pulleys = {sheave("block", Vec2(-2 * r, 0), WrapSide::Right),
                  sheave("world", Vec2(3 * r, top), WrapSide::Left),
                  sheave("block", Vec2(2 * r, 0), WrapSide::Right),
                  sheave("world", Vec2(7 * r, top), WrapSide::Left)};
  rope.end = {"effort", Vec2(0, 0.1)};
  s.cables = {rope};
  return s;
}

}  // namespace cablelab
