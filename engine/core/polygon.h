// Convex polygon checks shared by the scene validator, the wrap geometry and the loaders.
#pragma once

#include <span>

#include "engine/core/math.h"

namespace cablelab {

/// True when the vertices are a strictly convex polygon in counter-clockwise order (>= 3).
bool isConvexCCW(std::span<const Vec2> polygon);

}  // namespace cablelab
