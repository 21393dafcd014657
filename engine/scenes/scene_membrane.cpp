// Chapter 3: a weighted point pressed into an elastic band (cable + Hooke spring with preload and
// damping) stretched between two pulleys. It settles where T (u1 + u2) balances its weight.
#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makeMembraneScene(const SceneParams& p) {
  const double w = p.at("width");
  SceneDef s;
  s.name = "membrane";
  s.description = "a weighted point pressed into an elastic band between two pulleys";
  s.view = {Vec2(0, -0.1 * w), 1.0 * w};
  s.substeps = 4;

  BodyDef finger;
  finger.name = "finger";
  finger.mass = p.at("mass");
  finger.position = Vec2(p.at("x0"), 0.05 * w);
  finger.fixedRotation = true;
  finger.linearDamping = 0.5;
  ShapeDef dot;
  dot.radius = 0.02 * w;
  finger.shapes.push_back(dot);
  finger.shapes.back().sensor = true;
  s.bodies = {finger};

  CableDef band;
  band.name = "band";
  band.start = {"world", Vec2(-0.5 * w, 0)};
  band.end = {"world", Vec2(0.5 * w, 0)};
  PulleyDef contact;  // comes from above: the band passes on its right
  contact.body = "finger";
  contact.side = WrapSide::Right;
  band.pulleys = {contact};
  band.restLength = w;
  band.stiffness = p.at("k");
  band.preload = p.at("preload");
  band.damping = p.at("damping");
  s.cables = {band};
  return s;
}

}  // namespace cablelab
