#include "ui/authoring_route.h"

#include <algorithm>
#include <cmath>

namespace cablelab::ui {
namespace {

/// The angle (rad, 0..pi) the route before -> at -> after turns at `at`, and its side.
double routeTurn(const Vec2& before, const Vec2& at, const Vec2& after, WrapSide* side) {
  const Vec2 in = at - before, out = after - at;
  // A left turn round the pulley puts it on the cable's left: the cable passes its right.
  *side = cross(in, out) > 0 ? WrapSide::Right : WrapSide::Left;
  return std::abs(std::atan2(cross(in, out), in.dot(out)));
}

}  // namespace

RouteStop routeStop(const BodyDef& def, const BodyState& s, const Vec2& p, bool eyelet) {
  RouteStop stop;
  stop.body = def.name;
  const ShapeDef& shape = def.shapes.front();
  const bool small = shape.kind == ShapeDef::Kind::Circle && shape.radius <= kEyeletRadius;
  stop.eyelet = eyelet || small;
  stop.local = small ? shape.center : snapped(rotate(p - s.position, -s.angle), kSnap);
  if (stop.eyelet) {
    stop.world = s.position + rotate(stop.local, s.angle);
  } else if (shape.kind == ShapeDef::Kind::Circle) {
    stop.world = s.position + rotate(shape.center, s.angle);
  } else {
    Vec2 centre = Vec2::Zero();
    for (const Vec2& v : shape.vertices) centre += v / static_cast<double>(shape.vertices.size());
    stop.world = s.position + rotate(centre, s.angle);
  }
  return stop;
}

CableDef routedCable(const SceneDef& scene, const std::string& name, const AnchorDef& start,
                     const Vec2& worldStart, const std::vector<RouteStop>& stops,
                     const AnchorDef& end, const Vec2& worldEnd) {
  CableDef c;
  c.name = name;
  c.start = start;
  c.end = end;
  for (size_t k = 0; k < stops.size(); ++k) {
    const RouteStop& stop = stops[k];
    PulleyDef p;
    p.body = stop.body;
    if (stop.eyelet) {  // threaded: in the path whatever the bend
      p.kind = PulleyDef::Kind::Point;
      p.point = stop.local;
      p.side = WrapSide::Threaded;
      c.pulleys.push_back(p);
      continue;
    }
    const Vec2 before = k == 0 ? worldStart : stops[k - 1].world;
    const Vec2 after = k + 1 < stops.size() ? stops[k + 1].world : worldEnd;
    p.turns = snapped(routeTurn(before, stop.world, after, &p.side) / (2 * M_PI), kFineSnap);
    const ShapeDef& shape = scene.bodies[findBodyIndex(scene, stop.body)].shapes.front();
    if (shape.kind == ShapeDef::Kind::Circle) {
      p.kind = PulleyDef::Kind::Circle;
      p.point = shape.center;
      p.radius = shape.radius;
    } else {
      p.kind = PulleyDef::Kind::Polygon;  // the body's own polygon
    }
    c.pulleys.push_back(p);
  }
  return c;
}

std::string routeProblem(const World& world, int index) {
  const Cable& cable = world.cable(index);
  const CableDef& def = cable.def();
  for (size_t j = 0; j < def.pulleys.size(); ++j) {
    const bool inPath =
        std::any_of(cable.path().begin(), cable.path().end(),
                    [&](const WrapPoint& w) { return cable.scenePulley(w.pulley) == int(j); });
    if (inPath) continue;
    const PulleyDef& p = def.pulleys[j];
    if (p.side == WrapSide::Auto)
      return "The cable does not touch " + p.body +
             ", so it runs straight past it. With side "
             "auto the cable goes round a pulley only once it touches it.";
    return "The cable cannot go round " + p.body +
           ": it would not touch it there (an end is "
           "inside it, or the cable runs straight past it). Click the pulleys so that the cable "
           "bends round each one.";
  }
  return "";
}

}  // namespace cablelab::ui
