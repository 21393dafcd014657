// An Atwood machine over a massive wheel the cable does not slip on: the wheel turns with the
// cable, a = g (m1 - m2) / (m1 + m2 + I / r^2) and |v| = r |omega| (docs/wheels.md).
#include "engine/scenes/scene_parts.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makeWheelScene(const SceneParams& p) {
  const double r = p.at("r"), y = 4.0;
  SceneDef s;
  s.name = "wheel";
  s.description =
      "Atwood machine over a no-slip wheel: try --set I=0 (a massless wheel), m1=m2 (balance), "
      "or drag a box and watch the wheel's spoke turn";
  s.view = {Vec2(0, 1.5), 7.0};

  BodyDef wheel = wheelBody("wheel", Vec2(0, y), r);  // the boxes hang below it
  wheel.mass = 1.0;
  wheel.inertia = p.at("I");
  s.bodies = {wheel, boxBody("left", Vec2(-r, y - 1.0), p.at("m1"), 0.08),
              boxBody("right", Vec2(r, y - 4.5), p.at("m2"), 0.08)};
  if (p.at("I") == 0) s.bodies[0].inertia = 1e-9;  // "0" means as light as Box2D allows

  JointDef axle;
  axle.name = "axle";
  axle.bodyB = "wheel";
  axle.anchor = Vec2(0, y);
  s.joints = {axle};

  CableDef cable;
  cable.name = "cable";
  cable.start = {"left", Vec2(0, 0.08)};
  PulleyDef rim;
  rim.kind = PulleyDef::Kind::Circle;
  rim.body = "wheel";
  rim.radius = r;
  rim.side = WrapSide::Left;  // up the left side, clockwise over the top
  rim.grip = Grip::NoSlip;
  rim.turns = 0.5;
  cable.pulleys = {rim};
  cable.end = {"right", Vec2(0, 0.08)};
  s.cables = {cable};
  return s;
}

}  // namespace cablelab
