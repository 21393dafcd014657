// A polygon body in elastic slings: a scene for the long-run energy tests and the event-cut
// benchmark (many wrap changes: the vertices in the sling change as the body turns).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/model/scene.h"

namespace cablelab::test {

inline std::vector<Vec2> regularPolygon(int sides, double radius) {
  std::vector<Vec2> v;
  for (int i = 0; i < sides; ++i) {
    const double a = 2 * M_PI * i / sides;
    v.push_back(radius * Vec2(std::cos(a), std::sin(a)));
  }
  return v;
}

// A free 0.6 m square of `mass` and `inertia` at `position`, its shape a sensor (it touches
// nothing), for a cable to wrap.
inline BodyDef sensorSquare(const std::string& name, const Vec2& position, double mass,
                            double inertia) {
  BodyDef body;
  body.name = name;
  body.position = position;
  body.mass = mass;
  body.inertia = inertia;
  ShapeDef quad;
  quad.kind = ShapeDef::Kind::Polygon;
  quad.vertices = {Vec2(-0.3, -0.3), Vec2(0.3, -0.3), Vec2(0.3, 0.3), Vec2(-0.3, 0.3)};
  quad.sensor = true;
  body.shapes = {quad};
  return body;
}

// A free polygon body (no shapes: nothing to touch) of 1 kg at the origin, spinning at `spin`,
// in `cables` undamped elastic cables from (-1.5, y) to (1.5, y) that pass under it (each wraps
// it from below: the body sits in them as in a sling), y spread over [0.05, 0.15].
inline SceneDef sling(int sides, int cables, double spin, double k, int substeps) {
  SceneDef s;
  s.name = "sling";
  BodyDef body;
  body.name = "body";
  body.mass = 1;
  const double radius = 0.2;
  body.inertia = 0.5 * radius * radius;  // about a disc's: the polygon's is close
  body.angularVelocity = spin;
  s.bodies = {body};
  for (int c = 0; c < cables; ++c) {
    const double y = cables == 1 ? 0.1 : 0.05 + 0.1 * c / (cables - 1);
    CableDef cable;
    cable.name = "c" + std::to_string(c);
    cable.start = {"world", Vec2(-1.5, y)};
    cable.end = {"world", Vec2(1.5, y)};
    PulleyDef wrap;
    wrap.kind = PulleyDef::Kind::Polygon;
    wrap.body = "body";
    wrap.vertices = regularPolygon(sides, radius);
    wrap.side = WrapSide::Right;  // walking +x, the cable passes under the body
    cable.pulleys = {wrap};
    cable.restLength = 3.0;
    cable.stiffness = k / cables;
    s.cables.push_back(cable);
  }
  s.substeps = substeps;
  return s;
}

}  // namespace cablelab::test
