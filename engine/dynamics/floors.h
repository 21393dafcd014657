// Floors (docs/cables.md, "Floors"): a cable segment cannot go below zero length. A segment
// between two different bodies, one of which the solve moves, shorter than kFloorWatch (its
// length between its contact points: a circle's tangent point, floorGap) gets a unilateral row
// keeping it at least kFloorLength long, so a body that reaches its pulley
// stops there (an inelastic stop, as a real block at a real pulley). Both cable solves (the
// midpoint one and the main one with joints) add these rows. Private to engine/dynamics.
#pragma once

#include <cmath>
#include <cstddef>
#include <span>

#include "engine/cable/cable.h"

namespace cablelab {

inline constexpr double kFloorWatch = 0.5;    ///< m: segments shorter than this get a floor row
inline constexpr double kFloorLength = 0.01;  ///< m: the closest two points of a segment come

/// Where segment (p, q) of a path touches p and q: a circle's tangent point, else the point.
inline Vec2 floorFrom(const WrapPoint& p) {
  return p.radius == 0 ? p.world : p.tangentOut;
}
inline Vec2 floorTo(const WrapPoint& q) {
  return q.radius == 0 ? q.world : q.tangentIn;
}

/// The gap a floor keeps open: the segment's length as the path has it, between its contact
/// points (a circle's tangent point). Next to a wheel that is the tangent segment, which goes to
/// zero where a box hauled up along it reaches the rim.
inline double floorGap(const WrapPoint& p, const WrapPoint& q) {
  return (floorTo(q) - floorFrom(p)).norm();
}

/// Whether segment i (points i and i + 1) of `path` needs a floor row; `moved(body)` says whether
/// the solve moves that body (the world, -1, never moves).
template <class Moved>
bool needsFloor(std::span<const WrapPoint> path, size_t i, Moved moved) {
  const int a = path[i].body, b = path[i + 1].body;
  return a != b && ((a >= 0 && moved(a)) || (b >= 0 && moved(b))) &&
         floorGap(path[i], path[i + 1]) < kFloorWatch;
}

}  // namespace cablelab
