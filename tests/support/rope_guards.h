// Checks shared by the wrap tests of polygon pulleys (docs/cables.md, "Polygons side by side"):
// the guards' warnings that a length jumped, and how deep a point went into a hull.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "engine/cable/wrap.h"
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

/// How deep the segment a -> b cuts `hull` (m: how far the hull reaches past its line on its
/// shallower side; 0 for an edge of one polygon's chain, which the rope lies along).
inline double cutDepth(const WrapPoint& a, const WrapPoint& b, const std::vector<Vec2>& hull) {
  if (a.kind == WrapPoint::Kind::Vertex && b.kind == WrapPoint::Kind::Vertex && a.body == b.body)
    return 0;
  if (!segmentCutsPolygon(a.world, b.world, hull)) return 0;
  double left = 0, right = 0;
  for (const Vec2& v : hull) {
    left = std::max(left, wrapSideDistance(a.world, b.world, v, WrapSide::Left));
    right = std::max(right, wrapSideDistance(a.world, b.world, v, WrapSide::Right));
  }
  return std::min(left, right);
}

}  // namespace cablelab::test
