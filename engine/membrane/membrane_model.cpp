#include "engine/membrane/membrane_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cablelab {

double membraneStretch(const MembraneGeometry& g, const Vec2& p) {
  return (p - g.a).norm() + (p - g.b).norm() - (g.a - g.b).norm();
}

Vec2 membraneDirectionSum(const MembraneGeometry& g, const Vec2& p) {
  return (p - g.a).normalized() + (p - g.b).normalized();
}

double membraneTension(const MembraneGeometry& g, const MembraneParams& m, const Vec2& p) {
  return m.k * std::max(0.0, membraneStretch(g, p) + m.preload);
}

Vec2 membraneForce(const MembraneGeometry& g, const MembraneParams& m, const Vec2& p) {
  return -membraneTension(g, m, p) * membraneDirectionSum(g, p);
}

double membraneEnergy(const MembraneGeometry& g, const MembraneParams& m, const Vec2& p) {
  const double extension = std::max(0.0, membraneStretch(g, p) + m.preload);
  return 0.5 * m.k * extension * extension;
}

double membraneForceAngleDeg(const MembraneGeometry& g, const Vec2& p) {
  const Vec2 pull = -membraneDirectionSum(g, p);
  return wrapAngleDeg(std::atan2(pull.y(), pull.x()) * 180.0 / std::numbers::pi);
}

double wrapAngleDeg(double degrees) {
  double wrapped = std::fmod(degrees, 360.0);  // in (-360, 360)
  if (wrapped > 180.0) wrapped -= 360.0;
  if (wrapped <= -180.0) wrapped += 360.0;
  return wrapped;
}

}  // namespace cablelab
