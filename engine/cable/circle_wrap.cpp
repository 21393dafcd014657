#include "engine/cable/circle_wrap.h"

#include <cmath>

namespace cablelab {

CircleTangent circleTangent(const Vec2& c0, double rho0, const Vec2& c1, double rho1) {
  // D = c1 - c0 = l u + delta n with delta = rho0 - rho1 (the tangent points differ by l u).
  CircleTangent t;
  const Vec2 d = c1 - c0;
  const double d2 = d.squaredNorm();
  const double delta = rho0 - rho1;
  const double l2 = d2 - delta * delta;
  if (d2 == 0) {
    t.degenerate = true;
    return t;
  }
  if (l2 <= 0) {
    // Overlapping circles: the limit of the tangent as they come to touch.
    t.degenerate = true;
    t.u = (-delta * perp(d) / d2).normalized();
    return t;
  }
  t.length = std::sqrt(l2);
  t.u = (t.length * d - delta * perp(d)) / d2;
  return t;
}

double nearestTurn(double angle, double reference) {
  constexpr double kTurn = 2 * M_PI;
  return angle + kTurn * std::round((reference - angle) / kTurn);
}

double turnAngle(const Vec2& uIn, const Vec2& uOut, double rho, double previous) {
  // Clockwise for rho > 0, counter-clockwise for rho < 0.
  const double ccw = std::atan2(cross(uIn, uOut), uIn.dot(uOut));
  return nearestTurn(rho > 0 ? -ccw : ccw, previous);
}

namespace {

// World angle of the radius from the centre to the tangent point, C + rho perp(u).
double tangentAngle(const Vec2& u, double rho) {
  const Vec2 radius = rho > 0 ? perp(u) : Vec2(-perp(u));
  return std::atan2(radius.y(), radius.x());
}

}  // namespace

double arcToMark(const Vec2& u, double rho, double markAngle, double previous) {
  const double beta = tangentAngle(u, rho);
  return nearestTurn(rho > 0 ? beta - markAngle : markAngle - beta, previous);
}

double arcFromMark(const Vec2& u, double rho, double markAngle, double previous) {
  const double beta = tangentAngle(u, rho);
  return nearestTurn(rho > 0 ? markAngle - beta : beta - markAngle, previous);
}

}  // namespace cablelab
