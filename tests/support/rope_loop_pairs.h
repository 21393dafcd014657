// Two free polygons thrown into the loops of one rigid rope hung from (-1, 1) over a point pulley
// at (0, 1) to (1, 1), 60 Hz: the scenes of a random sweep (two n-gons of 3-8 sides, 0.15-0.3 m,
// 0.2/1/5 kg, thrown at up to 4 m/s, spinning at up to 4 rad/s), each pair named by its seed
// there. The contact-catch and knock tests use them.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "engine/model/scene_json.h"

namespace cablelab::test {

/// A regular polygon body: `sides` corners at `radius` from its centre, the first at `phase`.
struct Thrown {
  int sides;
  double radius, phase, mass;
  double vx, vy, spin;
};

struct LoopPair {
  int seed;  ///< of the sweep that found it
  Thrown a, b;
};

inline nlohmann::json thrownPolygonBody(const std::string& name, double x, const Thrown& t,
                                        double mass, double speedUp) {
  nlohmann::json vertices = nlohmann::json::array();
  for (int k = 0; k < t.sides; ++k) {
    const double angle = t.phase + 2 * M_PI * k / t.sides;
    vertices.push_back({t.radius * std::cos(angle), t.radius * std::sin(angle)});
  }
  return {{"name", name},
          {"position", {x, 0.0}},
          {"mass", mass},
          {"shapes", {{{"type", "polygon"}, {"vertices", vertices}, {"sensor", true}}}},
          {"velocity", {speedUp * t.vx, speedUp * t.vy}},
          {"angular_velocity", speedUp * t.spin}};
}

/// The pair in the rope's loops at 60 Hz, its throws `speedUp` times as fast, its masses
/// swapped if `swap`.
inline SceneDef ropeLoops(const LoopPair& p, double speedUp = 1, bool swap = false) {
  const nlohmann::json loop = {{"type", "polygon"}, {"side", "right"}, {"turns", 0.5}};
  nlohmann::json a = loop, b = loop;
  a["body"] = "a";
  b["body"] = "b";
  const nlohmann::json scene = {
      {"name", "loops"},
      {"dt", 1.0 / 60},
      {"bodies",
       {thrownPolygonBody("a", -0.5, p.a, swap ? p.b.mass : p.a.mass, speedUp),
        thrownPolygonBody("b", 0.5, p.b, swap ? p.a.mass : p.b.mass, speedUp)}},
      {"cables",
       {{{"name", "rope"},
         {"start", {{"body", "world"}, {"point", {-1.0, 1.0}}}},
         {"end", {{"body", "world"}, {"point", {1.0, 1.0}}}},
         {"pulleys", {a, {{"type", "point"}, {"point", {0.0, 1.0}}, {"side", "left"}}, b}}}}}};
  return sceneFromJson(scene, "rope loops");
}

}  // namespace cablelab::test
