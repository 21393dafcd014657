// Checks shared by the wrap tests of polygon pulleys (docs/cables.md, "Polygons side by side"):
// the guards' warnings that a length jumped, and how deep a point went into a hull.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "engine/core/math.h"
#include "engine/dynamics/world.h"

namespace cablelab::test {

/// The first warning of a guard that dropped or released a polygon, or of a wrap change that
/// moved a length by more than 1 mm (cable.h); "" if there is none.
inline std::string jumpWarning(const World& world) {
  for (const std::string& w : world.warnings())
    if (w.find("left the path") != std::string::npos ||
        w.find("released with a jump") != std::string::npos ||
        w.find("moved the length by") != std::string::npos)
      return w;
  return "";
}

/// How deep `p` lies inside the convex counter-clockwise `hull` (m; <= 0 outside).
inline double depthInside(const Vec2& p, const std::vector<Vec2>& hull) {
  double depth = 1e300;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Vec2 edge = hull[(i + 1) % hull.size()] - hull[i];
    depth = std::min(depth, cross(edge, p - hull[i]) / edge.norm());
  }
  return depth;
}

}  // namespace cablelab::test
