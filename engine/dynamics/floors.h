// Floors (docs/cables.md, "Floors"): a cable segment cannot go below zero length. A segment
// between two different bodies, one of which the solve moves, that is shorter than kFloorWatch
// gets a unilateral row keeping it at least kFloorLength long, so a body that reaches its pulley
// stops there (an inelastic stop, as a real block at a real pulley). Both cable solves (the
// midpoint one and the main one with joints) add these rows. Private to engine/dynamics.
#pragma once

#include <cstddef>
#include <span>

#include "engine/cable/cable.h"

namespace cablelab {

inline constexpr double kFloorWatch = 0.5;    ///< m: segments shorter than this get a floor row
inline constexpr double kFloorLength = 0.01;  ///< m: the closest two points of a segment come

/// Whether segment i (points i and i + 1) of `path` needs a floor row; `moved(body)` says whether
/// the solve moves that body (the world, -1, never moves).
template <class Moved>
bool needsFloor(std::span<const WrapPoint> path, size_t i, Moved moved) {
  const int a = path[i].body, b = path[i + 1].body;
  const bool straight = path[i].radius == 0 && path[i + 1].radius == 0;  // not touching an arc
  return a != b && straight && ((a >= 0 && moved(a)) || (b >= 0 && moved(b))) &&
         (path[i + 1].world - path[i].world).norm() < kFloorWatch;
}

}  // namespace cablelab
