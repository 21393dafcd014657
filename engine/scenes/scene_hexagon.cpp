// Figure 2-4: a cable from a fixed anchor over a spinning hexagonal pulley to a swinging weight.
// The hexagon turns on a frictionless pivot, so the wrapped vertices change all the time.
#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makeHexagonScene(const SceneParams& p) {
  const double r = p.at("radius");
  SceneDef s;
  s.name = "hexagon";
  s.description = "a cable wrapping a spinning hexagonal pulley; wrap points come and go";
  s.view = {Vec2(0, -0.3), 3.5};
  s.substeps = 2;  // keeps the symplectic energy oscillation near 1% at 60 Hz

  BodyDef hex;
  hex.name = "hexagon";
  hex.mass = p.at("m_hexagon");
  hex.angularVelocity = p.at("omega");
  ShapeDef shape;
  shape.kind = ShapeDef::Kind::Polygon;
  for (int i = 0; i < 6; ++i)
    shape.vertices.push_back(r * Vec2(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3)));
  hex.shapes.push_back(shape);

  BodyDef weight;
  weight.name = "weight";
  weight.mass = p.at("m_weight");
  weight.position = Vec2(1.8 * r, -2.0 * r);
  weight.fixedRotation = true;
  ShapeDef box;
  box.kind = ShapeDef::Kind::Polygon;
  const double h = 0.1;
  box.vertices = {Vec2(-h, -h), Vec2(h, -h), Vec2(h, h), Vec2(-h, h)};
  box.sensor = true;  // swings past the hexagon without contact: energy is conserved
  weight.shapes.push_back(box);
  s.bodies = {hex, weight};

  JointDef pivot;
  pivot.name = "pivot";
  pivot.bodyB = "hexagon";
  pivot.anchor = Vec2::Zero();
  s.joints = {pivot};

  CableDef cable;
  cable.name = "cable";
  cable.start = {"world", Vec2(-3.0 * r, 1.6 * r)};
  PulleyDef wrap;
  wrap.kind = PulleyDef::Kind::Polygon;
  wrap.body = "hexagon";
  wrap.side = WrapSide::Left;  // over the top
  cable.pulleys = {wrap};
  cable.end = {"weight", Vec2::Zero()};
  s.cables = {cable};
  return s;
}

}  // namespace cablelab
