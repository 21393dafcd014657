// Contacts between a polygon pulley and its neighbours on a cable (docs/cables.md, "Points inside
// a hull"): a neighbouring polygon pulley on another body, or an anchor or point pulley fixed in
// the world, may not enter the polygon's hull, whatever the bodies' own shapes (pulleys are often
// sensors). Box2D keeps them apart (box2d_bridge.cpp): the rope then always has a taut path round
// each polygon and no guard has to drop one.
#pragma once

#include <vector>

#include "engine/core/math.h"
#include "engine/model/scene.h"

namespace cablelab {

/// One pair kept apart: the polygon pulley on moving body `body` and its neighbour on body
/// `otherBody` (-1: the world), a polygon pulley (`otherPolygon`, in that body's frame) or, where
/// `otherPolygon` is empty, the point `point` fixed in the world.
struct HullContact {
  int body = -1;
  std::vector<Vec2> polygon;  ///< in `body`'s frame
  int otherBody = -1;
  std::vector<Vec2> otherPolygon;
  Vec2 point = Vec2::Zero();
};

/// The pairs of `scene`'s cables: each polygon pulley on a dynamic body with the pulley or anchor
/// next to it in the cable's list, when that is a polygon pulley on another body or a point fixed
/// in the world. Pairs that overlap in the scene's pose (placed so on purpose) and polygons of
/// more vertices than Box2D holds are left out, as are repeats.
std::vector<HullContact> hullContacts(const SceneDef& scene);

}  // namespace cablelab
