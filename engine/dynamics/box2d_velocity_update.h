// Box2D's own velocity update of a free body (no contacts, no joints), in double precision:
// b2Island::Solve (Box2D 2.4) adds h (g + F / m) and h T / I, then damps what it got,
// v / (1 + h c), before it moves the body. Box2D does it in float, which leaves a body at rest
// moving at 1e-8 m/s; World sets this value after the step instead (world.cpp, advance).
#pragma once

#include "engine/cable/cable.h"
#include "engine/model/scene.h"

namespace cablelab {

/// The velocity (vx, vy, omega) Box2D gives `body` (state s, definition d) over a step of h under
/// gravity g and load (Fx, Fy, torque), damping included.
inline Vec3 box2dVelocity(const BodyState& s, const BodyDef& d, const Vec2& g, const Vec3& load,
                          double h) {
  const Vec2 v = (s.velocity + h * (g + s.invMass * load.head<2>())) / (1 + h * d.linearDamping);
  const double w = (s.angularVelocity + h * s.invInertia * load.z()) / (1 + h * d.angularDamping);
  return {v.x(), v.y(), w};
}

}  // namespace cablelab
