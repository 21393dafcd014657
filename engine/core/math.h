// Small 2D helpers on Eigen vectors. Double precision throughout the engine.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace cablelab {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// z-component of the 3D cross product (a.x, a.y, 0) x (b.x, b.y, 0).
inline double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// a rotated by +90 degrees: the velocity of a point at offset a on a body spinning at 1 rad/s.
inline Vec2 perp(const Vec2& a) {
  return {-a.y(), a.x()};
}

/// a rotated by the angle whose cosine and sine are c and s (for many points on one body).
inline Vec2 rotate(const Vec2& a, double c, double s) {
  return {c * a.x() - s * a.y(), s * a.x() + c * a.y()};
}

/// a rotated by angle (radians).
inline Vec2 rotate(const Vec2& a, double angle) {
  return rotate(a, std::cos(angle), std::sin(angle));
}

inline bool isFinite(const Vec2& a) {
  return std::isfinite(a.x()) && std::isfinite(a.y());
}

}  // namespace cablelab
