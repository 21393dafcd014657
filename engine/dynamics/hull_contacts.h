// Contacts between a polygon pulley and its neighbours on a cable (docs/cables.md, "Points inside
// a hull"): another polygon pulley of the cable, or an anchor or point pulley of it fixed in the
// world or on another body, may not enter the polygon's hull, whatever the bodies' own shapes
// (pulleys are often sensors). Box2D keeps them apart (box2d_bridge.cpp), an elastic rope's points
// on other bodies bouncing off first (hull_bounce.h): the rope then always has a taut path round
// each polygon and no guard has to drop one.
#pragma once

#include <vector>

#include "engine/core/math.h"
#include "engine/model/scene.h"

namespace cablelab {

/// One pair kept apart: the polygon pulley on body `body` (-1: the world) and its neighbour on body
/// `otherBody` (-1: the world), a polygon pulley (`otherPolygon`, in that body's frame) or, where
/// `otherPolygon` is empty, the point `point` (in that body's frame).
struct HullContact {
  int body = -1;
  std::vector<Vec2> polygon;  ///< in `body`'s frame
  int otherBody = -1;
  std::vector<Vec2> otherPolygon;
  Vec2 point = Vec2::Zero();
  /// The two overlap in the scene's pose (placed so on purpose): they touch only once they
  /// have come apart.
  bool apartFirst = false;
  /// A point of an elastic rope, on another body or fixed in the world (a free polygon riding
  /// in the rope's loop knocks its anchors): the knock keeps the energy (hull_bounce.h), Box2D's
  /// contact only holds a point that creeps in.
  bool bounces = false;
};

/// How a body of a scene answers a knock's impulse in closed form: freely (no joint), or turning
/// about `pivot` (in its frame) on one unlimited revolute joint to the world. `known` is false for
/// a body on other joints: its knocks stay Box2D's.
struct KnockResponse {
  bool known = true;
  bool pivoted = false;
  Vec2 pivot = Vec2::Zero();
};

/// Per body of `scene`.
std::vector<KnockResponse> knockResponses(const SceneDef& scene);

/// Whether convex counter-clockwise polygons `p` and `q` overlap (no edge of either has the other
/// wholly outside it).
bool hullsOverlap(const std::vector<Vec2>& p, const std::vector<Vec2>& q);

/// The pairs of `scene`'s cables: each polygon pulley on a dynamic body with every other polygon
/// pulley on the same cable (on another body) and every point of the cable (an anchor, a point
/// pulley) fixed in the world or on another body, any of which becomes its neighbour on the path
/// once the pulleys between leave; and each polygon pulley held still (on the world, a static or a
/// kinematic body) with every point of the cable on a moving body (a bob the rope winds up onto
/// it). Pairs that overlap in the scene's pose (placed so on purpose) touch once apart. A point
/// whose body's shapes meet the polygon there (the bodies pass through each other by design),
/// polygons of more vertices than Box2D holds, shapeless bodies (point masses) and repeats are left
/// out.
std::vector<HullContact> hullContacts(const SceneDef& scene);

}  // namespace cablelab
