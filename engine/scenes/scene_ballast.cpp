// Thesis section 2.4.2: a point touching a taut cable that runs over a fixed pulley to a ballast.
// Analytic result (docs/model.md#dynamics): at t = 0 the ballast accelerates towards the pulley at
// 2 v0y^2 / l and the point not at all, whatever the masses.
#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makeBallastScene(const SceneParams& p) {
  const double l = p.at("l");
  SceneDef s;
  s.name = "ballast";
  s.description = "a point strikes a taut cable that ends in a ballast (thesis 2.4.2, gravity off)";
  s.gravity = Vec2::Zero();
  s.view = {Vec2(0, -0.4 * l), 3.2 * l};

  BodyDef point;
  point.name = "point";
  point.mass = p.at("m_point");
  point.velocity = Vec2(p.at("v0x"), p.at("v0y"));
  point.fixedRotation = true;
  ShapeDef dot;
  dot.radius = 0.03 * l;
  point.shapes.push_back(dot);
  point.shapes.back().sensor = true;

  BodyDef ballast;
  ballast.name = "ballast";
  ballast.mass = p.at("m_ballast");
  ballast.position = Vec2(l, -l);
  ballast.fixedRotation = true;
  ShapeDef box;
  box.kind = ShapeDef::Kind::Polygon;
  const double h = 0.06 * l;
  box.vertices = {Vec2(-h, -h), Vec2(h, -h), Vec2(h, h), Vec2(-h, h)};
  box.sensor = true;
  ballast.shapes.push_back(box);
  s.bodies = {point, ballast};

  CableDef cable;
  cable.name = "cable";
  cable.start = {"world", Vec2(-l, 0)};
  PulleyDef touch;  // the point pushes the cable from below: the cable passes on its left
  touch.body = "point";
  touch.side = WrapSide::Left;
  PulleyDef fixed;
  fixed.point = Vec2(l, 0);
  fixed.side = WrapSide::Threaded;
  cable.pulleys = {touch, fixed};
  cable.end = {"ballast", Vec2::Zero()};
  s.cables = {cable};
  return s;
}

}  // namespace cablelab
