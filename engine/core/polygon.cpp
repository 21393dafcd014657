#include "engine/core/polygon.h"

#include <cmath>

namespace cablelab {

namespace {

// Turns smaller than this (cross product of consecutive edges) count as collinear.
constexpr double kCollinear = 1e-12;

}  // namespace

bool isConvexCCW(std::span<const Vec2> polygon) {
  const size_t n = polygon.size();
  if (n < 3) return false;
  for (size_t i = 0; i < n; ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % n];
    const Vec2& c = polygon[(i + 2) % n];
    if (!isFinite(a) || cross(b - a, c - b) <= kCollinear) return false;
  }
  // A strictly left-turning closed chain is convex only if it winds once.
  double turned = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec2 e0 = polygon[(i + 1) % n] - polygon[i];
    const Vec2 e1 = polygon[(i + 2) % n] - polygon[(i + 1) % n];
    turned += std::atan2(cross(e0, e1), e0.dot(e1));
  }
  return std::abs(turned - 2 * M_PI) < 1e-6;
}

}  // namespace cablelab
