// A rope wound `turns` turns round a fixed drum with capstan friction mu: it holds while
// m_load / m_hold <= e^(mu theta) (theta = 2 pi turns) and slips beyond, the two tensions in that
// ratio (Euler-Eytelwein, docs/wheels.md). The load hangs from the drum's left side; the rope
// leaves the drum along the tangent where the wrap ends and runs over a small pulley to `hold`.
#include <cmath>

#include "engine/scenes/scene_parts.h"
#include "engine/scenes/scene_registry.h"

namespace cablelab {

SceneDef makeCapstanScene(const SceneParams& p) {
  const double r = p.at("r"), turns = p.at("turns"), y = 3.0, reach = 1.2;
  const Vec2 centre(0, y);
  // Clockwise from the leftmost point by theta; the rope leaves along the clockwise tangent.
  const double leave = M_PI - 2 * M_PI * turns;
  const Vec2 exitPoint = centre + r * Vec2(std::cos(leave), std::sin(leave));
  const Vec2 direction(std::sin(leave), -std::cos(leave));
  const Vec2 redirect = exitPoint + reach * direction;

  SceneDef s;
  s.name = "capstan";
  s.description =
      "rope round a fixed drum with friction: holds while m_load/m_hold <= e^(mu theta); try "
      "--set m_load=6 (slips), mu=0 (no friction), turns=1.75";
  s.view = {Vec2(redirect.x() * 0.5, y - 1.0), 5.0};

  BodyDef drum = wheelBody("drum", centre, r);
  drum.type = BodyType::Static;
  s.bodies = {drum, boxBody("load", Vec2(-r, y - 1.5), p.at("m_load"), 0.1),
              boxBody("hold", redirect + Vec2(0, -1.5), p.at("m_hold"), 0.1)};

  CableDef rope;
  rope.name = "rope";
  rope.start = {"load", Vec2(0, 0.1)};
  PulleyDef wrap;
  wrap.kind = PulleyDef::Kind::Circle;
  wrap.body = "drum";
  wrap.radius = r;
  wrap.side = WrapSide::Left;
  wrap.grip = p.at("mu") > 0 ? Grip::Capstan : Grip::Frictionless;
  wrap.mu = p.at("mu");
  wrap.turns = turns;
  PulleyDef over;
  over.point = redirect;
  over.side = WrapSide::Threaded;
  rope.pulleys = {wrap, over};
  rope.end = {"hold", Vec2(0, 0.1)};
  s.cables = {rope};
  return s;
}

}  // namespace cablelab
