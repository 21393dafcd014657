// Cable routing for the sandbox's cable tool: the clicked start, pulleys and end become a CableDef
// that runs over every clicked pulley in click order.
//
// Needs: the engine's scene definitions and World. Each pulley's side comes from the route's turn
// there (turning right round it: the pulley lies on the cable's right, WrapSide::Left), and
// circles and polygons get `turns` = the angle the route turns there, so the engine puts them in
// the path from the start even where the straight cable would miss them (docs/model.md, Guards).
// The rest length is left to the engine: the routed length at the initial pose.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/model/scene.h"

namespace cablelab::ui {

/// Clicks snap to whole centimetres, pulley corners and wrap turns to 1e-4, so that a scene built
/// by clicks reads as round numbers in its file (and can be typed by hand).
inline constexpr double kSnap = 100;  ///< clicks, per metre
inline constexpr double kFineSnap = 10000;

/// `v` rounded to 1/perUnit (k / perUnit: the double a file's decimal number reads as).
inline double snapped(double v, double perUnit) {
  return std::round(v * perUnit) / perUnit;
}
inline Vec2 snapped(const Vec2& p, double perUnit) {
  return Vec2(snapped(p.x(), perUnit), snapped(p.y(), perUnit));
}

/// Circle shapes up to this radius (m) are eyelets: the cable threads them as a point pulley.
inline constexpr double kEyeletRadius = 0.03;

/// One pulley clicked on the route: a body and, for an eyelet on a body, the clicked point.
struct RouteStop {
  std::string body;           ///< the body the pulley is on
  Vec2 world = Vec2::Zero();  ///< where the route bends (the pulley's centre or the eyelet), m
  bool eyelet = false;        ///< true: a point pulley at `local` (Alt+click on any body)
  Vec2 local = Vec2::Zero();  ///< eyelet: the clicked point, body frame (m)
};

/// The stop for a click on body `b` at world point `p` (its state `s`): an eyelet when `eyelet`
/// or when the body is a small circle, else the body's first shape (its centre for the route).
RouteStop routeStop(const BodyDef& def, const BodyState& s, const Vec2& p, bool eyelet);

/// The cable start -> stops -> end (worldStart, worldEnd: the clicked end points, m).
CableDef routedCable(const SceneDef& scene, const std::string& name, const AnchorDef& start,
                     const Vec2& worldStart, const std::vector<RouteStop>& stops,
                     const AnchorDef& end, const Vec2& worldEnd);

/// Empty when every pulley of cable `index` is in the world's path; else a sentence for
/// students naming the first pulley the cable does not go round and why.
std::string routeProblem(const World& world, int index);

}  // namespace cablelab::ui
