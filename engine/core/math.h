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

/// The cosine and sine of an angle (radians). Zero, the angle of a body that never turns (fixed
/// rotation, a box between fingers), costs no sincos: cos 0 = 1 and sin(+-0) = +-0 exactly.
inline void cosSin(double angle, double& c, double& s) {
  if (angle == 0) {
    c = 1, s = angle;
    return;
  }
  c = std::cos(angle), s = std::sin(angle);
}

/// a rotated by angle (radians).
inline Vec2 rotate(const Vec2& a, double angle) {
  double c, s;
  cosSin(angle, c, s);
  return rotate(a, c, s);
}

inline bool isFinite(const Vec2& a) {
  return std::isfinite(a.x()) && std::isfinite(a.y());
}

}  // namespace cablelab
