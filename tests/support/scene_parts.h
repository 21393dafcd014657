// Parts the tests' hand-built scenes share: a sensor box shape (nothing touches it) and a body
// pivoted on the world.
#pragma once

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

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

/// A regular polygon of `sides` corners `radius` from the body origin, the first at angle
/// `phase`, a sensor.
inline ShapeDef sensorPolygon(int sides, double radius, double phase = 0) {
  ShapeDef polygon = sensorBox(0, 0);
  polygon.vertices.clear();
  for (int k = 0; k < sides; ++k) {
    const double a = phase + 2 * M_PI * k / sides;
    polygon.vertices.push_back(radius * Vec2(std::cos(a), std::sin(a)));
  }
  return polygon;
}

/// A 0.2 m sensor box of `mass` at `at` that does not turn: a weight hanging on a rope.
inline BodyDef hangingMass(const std::string& name, const Vec2& at, double mass) {
  BodyDef b;
  b.name = name;
  b.position = at;
  b.mass = mass;
  b.fixedRotation = true;
  b.shapes = {sensorBox(0.1, 0.1)};
  return b;
}

/// A 5 cm sensor disc of `mass` at `position` moving at `velocity` that does not turn: a puck
/// that only its cables and their floors act on.
inline BodyDef puck(const std::string& name, const Vec2& position, const Vec2& velocity,
                    double mass) {
  BodyDef b;
  b.name = name;
  b.position = position;
  b.velocity = velocity;
  b.mass = mass;
  b.inertia = 1e-3;
  b.fixedRotation = true;
  b.shapes = {sensorDisc(0.05)};
  return b;
}

/// Masses m1 and m2 (kg) hanging at (-0.2, 1.5) and (0.2, 1.5) on the ends of a band, 0.1 m above
/// them, that runs over the top of the fixed polygon `vertices` from the start (half a turn in
/// all) with capstan friction `mu` (frictionless at 0). The band, "band", is left to the caller:
/// its stiffness, damping and material.
inline SceneDef bandOverPolygon(const std::vector<Vec2>& vertices, double mu, double m1,
                                double m2) {
  SceneDef s;
  s.name = "band-over-polygon";
  s.bodies = {hangingMass("left", Vec2(-0.2, 1.5), m1), hangingMass("right", Vec2(0.2, 1.5), m2)};
  PulleyDef over;
  over.kind = PulleyDef::Kind::Polygon;
  over.side = WrapSide::Left;
  over.turns = 0.5;
  over.vertices = vertices;
  over.grip = mu > 0 ? Grip::Capstan : Grip::Frictionless;
  over.mu = mu;
  CableDef band;
  band.name = "band";
  band.start = {"left", Vec2(0, 0.1)};
  band.end = {"right", Vec2(0, 0.1)};
  band.pulleys = {over};
  s.cables = {band};
  return s;
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

/// A 0.5 m hexagon "hexagon" (`hexagonMass` kg, `hexagonInertia` kg m^2) spinning at `spin` rad/s
/// on a pivot at the origin, and a rigid rope "rope" from the world point `from` round its left to
/// a weight "weight" of `mass` kg at `weightAt` (the caller sets a stiffness or a throw).
inline SceneDef ropeOverASpinningHexagon(double hexagonMass, double hexagonInertia, double spin,
                                         const Vec2& from, const Vec2& weightAt, double mass) {
  SceneDef scene;
  BodyDef hexagon;
  hexagon.name = "hexagon";
  hexagon.mass = hexagonMass;
  hexagon.inertia = hexagonInertia;
  hexagon.angularVelocity = spin;
  hexagon.shapes = {sensorPolygon(6, 0.5)};
  scene.bodies = {hexagon, hangingMass("weight", weightAt, mass)};
  scene.joints = {worldPivot("hexagon", Vec2(0, 0))};
  CableDef rope;
  rope.name = "rope";
  rope.start.body = "world";
  rope.start.point = from;
  PulleyDef wrap;
  wrap.body = "hexagon";
  wrap.kind = PulleyDef::Kind::Polygon;
  wrap.side = WrapSide::Left;
  wrap.vertices = hexagon.shapes[0].vertices;
  rope.pulleys = {wrap};
  rope.end.body = "weight";
  scene.cables = {rope};
  return scene;
}

/// Two `sides`-gons "A" and "B" of corner radius 0.12 m and 1 kg, pinned at (-+half, 0) and
/// spinning at `spinA` and `spinB` rad/s (B's first corner at `phaseB`), their shapes of
/// `restitution`; a rope "rope" from the world at (-0.9, -1) over both (left) and a world point at
/// (0.9, 0.3) down to a weight "weight" of `weight` kg (docs/knocks.md, "Two pulleys knocking").
inline SceneDef pinnedPolygonPairOnOneRope(int sides, double half, double spinA, double spinB,
                                           double phaseB, double restitution, double weight) {
  SceneDef s;
  for (const auto& [name, x, spin, phase] :
       {std::tuple{"A", -half, spinA, 0.0}, std::tuple{"B", half, spinB, phaseB}}) {
    BodyDef b;
    b.name = name;
    b.position = Vec2(x, 0);
    b.mass = 1;
    b.angularVelocity = spin;
    b.shapes = {sensorPolygon(sides, 0.12, phase)};
    b.shapes[0].restitution = restitution;
    s.bodies.push_back(b);
    JointDef pin = worldPivot(name, Vec2(x, 0));
    pin.name = std::string("pin") + name;
    s.joints.push_back(pin);
  }
  s.bodies.push_back(hangingMass("weight", Vec2(0.9, -1), weight));
  CableDef rope;
  rope.name = "rope";
  rope.start = {"world", Vec2(-0.9, -1)};
  for (const char* body : {"A", "B"}) {
    PulleyDef over;
    over.kind = PulleyDef::Kind::Polygon;
    over.body = body;
    over.side = WrapSide::Left;
    rope.pulleys.push_back(over);
  }
  PulleyDef point;
  point.kind = PulleyDef::Kind::Point;
  point.point = Vec2(0.9, 0.3);
  point.side = WrapSide::Threaded;
  rope.pulleys.push_back(point);
  rope.end = {"weight", Vec2::Zero()};
  s.cables = {rope};
  return s;
}

/// An elastic rope "rope" from the body `start` threaded over world points `left` and `right` to
/// the body `end`: an Atwood machine's rope of `stiffness` N/m and `restLength` m.
inline CableDef elasticAtwoodRope(const std::string& start, const std::string& end,
                                  const Vec2& left, const Vec2& right, double stiffness,
                                  double restLength) {
  CableDef rope;
  rope.name = "rope";
  rope.start.body = start;
  rope.end.body = end;
  PulleyDef first, second;
  first.point = left;
  second.point = right;
  first.side = second.side = WrapSide::Threaded;
  rope.pulleys = {first, second};
  rope.stiffness = stiffness;
  rope.restLength = restLength;
  return rope;
}

}  // namespace cablelab::test
