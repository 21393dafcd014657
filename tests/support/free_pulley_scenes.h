// Points on moving bodies driven into a free polygon pulley of their own rope (issue 36, item 4;
// docs/cables.md, "Points inside a hull"): a weight hauled up against a polygon on a pivot, and
// polygons riding in the loops of a rope whose middle point is on a swinging bob. The pulleys are
// free (no rope is tied on them) and every shape is a sensor: only the rope's contacts touch.
#pragma once

#include <cmath>
#include <string>

#include "engine/model/scene.h"
#include "tests/support/scene_parts.h"

namespace cablelab::test {

/// An Atwood machine over a regular polygon of `sides` (0.3 m to its corners, 2 kg) on a free
/// pivot at the origin: a counterweight of `counterweight` kg hangs on the rope's left, 1 m
/// below, and hauls the rope's end, a weight of `weight` kg 1 m below on the right, up against
/// the polygon. The weight is a small disc (its anchor at its centre); the counterweight a
/// shapeless point mass. Nothing is damped. `stiffness` > 0: an elastic rope (N/m), its rest
/// length the length in this pose.
inline SceneDef weightHauledIntoAFreePolygon(int sides, double weight, double counterweight,
                                             double stiffness = 0) {
  SceneDef s;
  s.name = "weight_hauled_into_a_free_polygon";
  BodyDef polygon;
  polygon.name = "polygon";
  polygon.mass = 2;
  polygon.shapes = {sensorPolygon(sides, 0.3, M_PI / 2)};
  BodyDef load;
  load.name = "weight";
  load.position = Vec2(0.32, -1);
  load.mass = weight;
  load.fixedRotation = true;
  load.shapes = {sensorDisc(0.03)};
  BodyDef haul;
  haul.name = "counterweight";
  haul.position = Vec2(-0.32, -1);
  haul.mass = counterweight;
  haul.inertia = 0.01;
  s.bodies = {polygon, load, haul};
  s.joints = {worldPivot("polygon", Vec2::Zero())};
  CableDef rope;
  rope.name = "rope";
  rope.start = {"counterweight", Vec2::Zero()};
  PulleyDef over;
  over.kind = PulleyDef::Kind::Polygon;
  over.body = "polygon";
  over.side = WrapSide::Left;  // walking from the counterweight (left) up over the top
  over.turns = 0.5;            // over it from the start
  rope.pulleys = {over};
  rope.end = {"weight", Vec2::Zero()};
  rope.stiffness = stiffness;
  s.cables = {rope};
  return s;
}

/// The "free polygons riding in rope loops" with the rope's middle point on a bob: a rope
/// from (-1, 1) round polygon a (under it), over a point on a 1 kg bob hung on a rigid 1 m tether
/// from (0, 2), round polygon b, to (1, 1). The polygons (`sides` corners 0.25 m from their
/// centres, `mass` kg each) are thrown up towards the bob, which swings at `bobSpeed` m/s.
/// `stiffness` > 0: an elastic rope (N/m), its rest length the length in this pose.
inline SceneDef polygonsInLoopsUnderABob(int sides, double mass, double bobSpeed,
                                         double stiffness = 0) {
  SceneDef s;
  s.name = "polygons_in_loops_under_a_bob";
  auto polygon = [&](const std::string& name, double x, const Vec2& velocity, double spin) {
    BodyDef b;
    b.name = name;
    b.position = Vec2(x, 0);
    b.mass = mass;
    b.shapes = {sensorPolygon(sides, 0.25, M_PI / 4)};
    b.velocity = velocity;
    b.angularVelocity = spin;
    return b;
  };
  BodyDef bob;
  bob.name = "bob";
  bob.position = Vec2(0, 1);
  bob.velocity = Vec2(bobSpeed, 0);
  bob.mass = 1;
  bob.fixedRotation = true;
  bob.shapes = {sensorDisc(0.05)};
  s.bodies = {polygon("a", -0.5, Vec2(-3, 3), 3), polygon("b", 0.5, Vec2(3, 1.5), -2), bob};
  CableDef tether;
  tether.name = "tether";
  tether.start = {"world", Vec2(0, 2)};
  tether.end = {"bob", Vec2::Zero()};
  CableDef rope;
  rope.name = "rope";
  rope.start = {"world", Vec2(-1, 1)};
  rope.end = {"world", Vec2(1, 1)};
  PulleyDef a, middle, b;
  a.kind = b.kind = PulleyDef::Kind::Polygon;
  a.body = "a";
  b.body = "b";
  a.side = b.side = WrapSide::Right;
  a.turns = b.turns = 0.5;  // in their loops from the start
  middle.body = "bob";
  middle.side = WrapSide::Left;
  rope.pulleys = {a, middle, b};
  rope.stiffness = stiffness;
  s.cables = {rope, tether};
  return s;
}

}  // namespace cablelab::test
