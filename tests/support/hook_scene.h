// A square whirled round a cable's end anchor on a tether, so that the cable winds round it and
// unwinds (more than half a turn, then whole turns, round a polygon beyond an end anchor): the
// hook tests and the long run use it.
#pragma once

#include <cmath>
#include <string>

#include "engine/model/scene.h"

namespace cablelab::test {

// No gravity. A 1 kg square bob (0.2 m, no shapes: nothing to touch) on a stiff elastic 1 m
// tether from the world point B = (0, 0), starting at (-0.98, -0.2) and moving up at `speed`
// (clockwise round B). An undamped elastic rope (stiffness k, preload: taut from the start) runs
// from A = (-2, 0) to B; the bob swings up through it from below, so the rope bends over the bob,
// and the further the bob goes round B the more it winds round it (past B: more than half a
// turn, then whole turns), which slows the bob until it swings back and unwinds. Nothing
// touches, nothing is damped: energy is kept.
inline SceneDef whirl(double speed, double k, double preload, int substeps) {
  SceneDef s;
  s.name = "whirl";
  s.gravity = Vec2::Zero();
  BodyDef bob;
  bob.name = "bob";
  bob.mass = 1;
  bob.inertia = 0.2 * 0.2 / 6;  // a uniform 0.2 m square
  bob.position = Vec2(-std::sqrt(1 - 0.04), -0.2);
  bob.velocity = speed * Vec2(0.2, std::sqrt(1 - 0.04));  // along the circle round B, up
  s.bodies = {bob};
  CableDef tether;
  tether.name = "tether";
  tether.start = {"world", Vec2::Zero()};
  tether.end = {"bob", Vec2::Zero()};
  tether.stiffness = 4000;
  CableDef rope;
  rope.name = "rope";
  rope.start = {"world", Vec2(-2, 0)};
  PulleyDef square;
  square.kind = PulleyDef::Kind::Polygon;
  square.body = "bob";
  square.vertices = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1), Vec2(-0.1, 0.1)};
  square.side = WrapSide::Left;  // walking from A to B (+x) the bob lifts it from below
  rope.pulleys = {square};
  rope.end = {"world", Vec2::Zero()};
  rope.restLength = 2;
  rope.stiffness = k;
  rope.preload = preload;
  s.cables = {tether, rope};
  s.substeps = substeps;
  return s;
}

}  // namespace cablelab::test
