// Circle pulleys: the tangent between two circles with signed radii, and wrap angles that stay
// continuous over many turns (docs/wheels.md).
//
// A signed radius rho carries the winding side: rho = +r when the cable passes on the circle's
// left (WrapSide::Left: the circle lies on the cable's right and the cable turns clockwise round
// it), rho = -r for Right. Points and polygon vertices are circles of radius 0. Walking along the
// cable with unit direction u and left normal n = perp(u), the cable touches a circle with centre
// C at C + rho n.
#pragma once

#include "engine/core/math.h"

namespace cablelab {

/// The straight piece of cable between two circles (centres c0 -> c1, signed radii rho0, rho1).
struct CircleTangent {
  Vec2 u = Vec2(1, 0);      ///< unit direction, from circle 0 to circle 1
  double length = 0;        ///< m, tangent point to tangent point
  bool degenerate = false;  ///< the circles overlap (no tangent): length 0, u a limit direction
  Vec2 from(const Vec2& c0, double rho0) const { return c0 + rho0 * perp(u); }
  Vec2 to(const Vec2& c1, double rho1) const { return c1 + rho1 * perp(u); }
};

/// Common tangent with the winding sides given by the signs of rho0 and rho1.
CircleTangent circleTangent(const Vec2& c0, double rho0, const Vec2& c1, double rho1);

/// angle + 2 pi k for the whole k that lands nearest to `reference` (rad).
double nearestTurn(double angle, double reference);

/// Angle the cable turns on a circle of signed radius rho between incoming direction uIn and
/// outgoing uOut, in the winding sense (>= 0 while wrapped), on the branch nearest `previous`.
double turnAngle(const Vec2& uIn, const Vec2& uOut, double rho, double previous);

/// Angle from the tangent point (direction u of the cable there) to a material mark at world
/// angle markAngle (rad) in the winding sense, for a cable ENDING on the circle (a drum, or the
/// incoming side of a wheel it does not slip on); nearest `previous`.
double arcToMark(const Vec2& u, double rho, double markAngle, double previous);
/// The same for a cable STARTING on the circle: from the mark to the tangent point.
double arcFromMark(const Vec2& u, double rho, double markAngle, double previous);

}  // namespace cablelab
