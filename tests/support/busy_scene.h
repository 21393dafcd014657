// A busy scene for the long run (issue 11): built-in scenes side by side in one world, each moved
// out of the others' way, plus a ground. Rigid cables over a spinning hexagon (wrap changes all
// the time, a pivot joint), a square spinning in an elastic sling, an undamped elastic band
// pressed by a point, an Atwood machine over two pulleys whose heavier box lands on the ground
// (contact, friction) while the lighter one is held at its pulley (a floor), and optionally the
// hand (membranes, servos, joints, the box between the fingers).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/dynamics/world.h"
#include "engine/model/scene.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/sling_scene.h"

namespace cablelab::test {

// Appends `part` to `into`, its names prefixed and everything in the world frame moved by
// `offset` (body frames move with their bodies).
inline void addPart(SceneDef& into, SceneDef part, const std::string& prefix, const Vec2& offset) {
  auto rename = [&](std::string& body) {
    if (body != "world") body = prefix + body;
  };
  auto place = [&](const std::string& body, Vec2& point) {
    if (body == "world") point += offset;
  };
  for (BodyDef& b : part.bodies) {
    b.name = prefix + b.name;
    b.position += offset;
  }
  for (JointDef& j : part.joints) {
    j.name = prefix + j.name;
    rename(j.bodyA);
    rename(j.bodyB);
    j.anchor += offset;
  }
  for (CableDef& c : part.cables) {
    c.name = prefix + c.name;
    for (AnchorDef* a : {&c.start, &c.end}) {
      place(a->body, a->point);
      rename(a->body);
    }
    for (PulleyDef& p : c.pulleys) {
      place(p.body, p.point);
      if (p.body == "world")
        for (Vec2& v : p.vertices) v += offset;
      rename(p.body);
    }
  }
  into.bodies.insert(into.bodies.end(), part.bodies.begin(), part.bodies.end());
  into.joints.insert(into.joints.end(), part.joints.begin(), part.joints.end());
  into.cables.insert(into.cables.end(), part.cables.begin(), part.cables.end());
  into.substeps = std::max(into.substeps, part.substeps);
}

// The parts with nothing damped, jointed or touching: a square spinning in an elastic sling and
// a point bouncing in an undamped elastic band.
// The built-in membrane with nothing damped, its point pressed 5 cm into the band and let go: it
// bounces in it for ever, never leaving it.
inline SceneDef undampedBand() {
  SceneDef band = makeScene("membrane", {{"damping", 0.0}});
  band.bodies[0].linearDamping = 0;
  band.bodies[0].position.y() = -0.05;
  return band;
}

inline SceneDef undampedParts() {
  SceneDef s;
  s.name = "undamped";
  addPart(s, test::sling(4, 1, 6.0, 400, 1), "sling.", Vec2(-4, 0));
  addPart(s, undampedBand(), "band.", Vec2(0, 0));
  return s;
}

inline SceneDef busy(bool withHand) {
  SceneDef s = undampedParts();
  s.name = "busy";
  addPart(s, makeScene("hexagon", {{"omega", 4.0}}), "hex.", Vec2(-8, 0));
  addPart(s, makeScene("pulley", {{"m_right", 1.3}}), "atwood.", Vec2(30, -20));
  // The ground under the Atwood machine's heavier (right) box, 2 m below it.
  BodyDef ground;
  ground.name = "ground";
  ground.type = BodyType::Static;
  ground.position = Vec2(40, -10);
  ShapeDef slab;
  slab.kind = ShapeDef::Kind::Polygon;
  slab.vertices = {Vec2(-4, -1), Vec2(4, -1), Vec2(4, 1), Vec2(-4, 1)};
  ground.shapes = {slab};
  s.bodies.push_back(ground);
  if (withHand) addPart(s, makeScene("hand"), "hand.", Vec2(0, 40));
  return s;
}

// The energy of one part of a world (its names start with `prefix`, as addPart gives them): kinetic
// + gravitational of its bodies plus the springs of its elastic cables; `kinetic` gets the
// kinetic part. A part with no cable or contact to the others keeps its own.
inline double partEnergy(const World& w, const std::string& prefix, double& kinetic) {
  auto ours = [&](const std::string& name) { return name.compare(0, prefix.size(), prefix) == 0; };
  double e = 0;
  kinetic = 0;
  for (int b = 0; b < static_cast<int>(w.scene().bodies.size()); ++b) {
    const BodyState& x = w.body(b);
    if (!ours(w.scene().bodies[b].name) || x.invMass == 0) continue;
    const double m = 1.0 / x.invMass;
    double k = 0.5 * m * x.velocity.squaredNorm();
    if (x.invInertia > 0) k += 0.5 * x.angularVelocity * x.angularVelocity / x.invInertia;
    kinetic += k;
    e += k - m * w.gravity().dot(x.position);
  }
  for (int c = 0; c < w.cableCount(); ++c) {
    const Cable& cable = w.cable(c);
    if (ours(cable.name()) && cable.elastic())
      e += 0.5 * cable.stiffness() * std::pow(std::max(0.0, cable.stretch()), 2);
  }
  return e;
}

}  // namespace cablelab::test
