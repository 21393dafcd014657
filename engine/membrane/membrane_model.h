// Membrane model of thesis chapter 3: an elastic band stretched between two point pulleys A and
// B, pushed out of line by a contact point p. Pure functions of the geometry and two parameters.
//
//   stretch(p) = |p - A| + |p - B| - |A - B|           (m, >= 0 by the triangle inequality)
//   T(p)       = k * max(0, stretch(p) + preload)      (N; a band cannot push)
//   F(p)       = -T(p) (u1 + u2),  u_i = (p - P_i) / |p - P_i|   (N, force of the band on p)
//   E(p)       = k/2 * max(0, stretch(p) + preload)^2  (J), and F = -dE/dp
//
// This follows docs/model.md#membranes, not the printed thesis: no factor 1/2 in F, and the preload
// enters with a plus sign (preload >= 0 is how far the band is already stretched when straight).
//
// Angles: the force direction is reported as atan2(F_y, F_x) in degrees, counter-clockwise from
// +x, in (-180, 180]. For a horizontal band with A left of B and p below it, F points up
// (angles near +90).
// Needs: Eigen (engine/core/math.h). No UI, no Box2D.
#pragma once

#include "engine/core/math.h"

namespace cablelab {

/// The two pulleys the band runs between (world frame, m). Must be distinct.
struct MembraneGeometry {
  Vec2 a = Vec2(-0.2, 0.0);  ///< pulley A (m)
  Vec2 b = Vec2(0.2, 0.0);   ///< pulley B (m)
};

/// The two fitted parameters.
struct MembraneParams {
  double k = 25.0;       ///< band stiffness (N/m), > 0
  double preload = 0.8;  ///< stretch of the straight band beyond its rest length (m), >= 0
};

/// |p - A| + |p - B| - |A - B| (m).
double membraneStretch(const MembraneGeometry& g, const Vec2& p);

/// u1 + u2, the sum of the unit vectors from each pulley to p (dimensionless, 2 x 1).
/// Its length is 0 on the segment AB (direction undefined) and up to 2 far away.
/// Precondition: p differs from both pulleys.
Vec2 membraneDirectionSum(const MembraneGeometry& g, const Vec2& p);

/// Band tension k * max(0, stretch + preload) (N).
double membraneTension(const MembraneGeometry& g, const MembraneParams& m, const Vec2& p);

/// Force of the band on the contact point, -T (u1 + u2) (N, 2 x 1).
Vec2 membraneForce(const MembraneGeometry& g, const MembraneParams& m, const Vec2& p);

/// Elastic energy k/2 max(0, stretch + preload)^2 (J); membraneForce is its negative gradient.
double membraneEnergy(const MembraneGeometry& g, const MembraneParams& m, const Vec2& p);

/// Direction of the band's pull on p, atan2 of -(u1 + u2), in degrees in (-180, 180].
/// Independent of k and preload: while the band is taut the force points this way.
double membraneForceAngleDeg(const MembraneGeometry& g, const Vec2& p);

/// Wraps an angle difference (degrees) into (-180, 180].
double wrapAngleDeg(double degrees);

}  // namespace cablelab
