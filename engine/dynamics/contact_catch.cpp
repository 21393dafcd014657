#include "engine/dynamics/contact_catch.h"

#include <algorithm>

#include "engine/dynamics/length_targets.h"

namespace cablelab {

namespace {

constexpr int kProjections = 4;  // Newton steps onto the rest length (the path turns as it moves)

// J M^-1 J^T of a cable's kinematics: how fast an impulse along the cable shortens it.
double lengthCompliance(const CableKinematics& kin, std::span<const BodyState> bodies) {
  double k = 0;
  for (const BodyJacobian& e : kin.jacobian) {
    const BodyState& b = bodies[e.body];
    k += b.invMass * e.d.head<2>().squaredNorm() + b.invInertia * e.d.z() * e.d.z();
  }
  return k;
}

bool caughtCable(const Cable& cable, std::span<const BodyState> bodies,
                 std::span<const char> knocked, std::span<const char> jointed) {
  if (cable.elastic() || cable.spanCount() != 1) return false;
  bool any = false;
  for (const BodyJacobian& e : cable.kinematics().jacobian) {
    if (!moves(bodies[e.body])) continue;
    if (jointed[e.body]) return false;
    any |= knocked[e.body] != 0;
  }
  return any;
}

// Moves the bodies' velocities (`velocities`) or their poses along M^-1 J^T by `impulse`
// (positive: shortening the cable).
void moveAlong(const CableKinematics& kin, std::span<BodyState> bodies, double impulse,
               bool velocities, std::vector<char>& moved) {
  for (const BodyJacobian& e : kin.jacobian) {
    BodyState& b = bodies[e.body];
    const Vec2 dx = -impulse * b.invMass * e.d.head<2>();
    const double dtheta = -impulse * b.invInertia * e.d.z();
    if (velocities) {
      b.velocity += dx;
      b.angularVelocity += dtheta;
    } else {
      b.position += dx;
      b.angle += dtheta;
    }
    moved[e.body] = 1;
  }
}

}  // namespace

bool catchCablesStretchedByContacts(std::span<Cable> cables, std::span<BodyState> bodies,
                                    std::span<const char> knocked, std::span<const char> jointed,
                                    std::vector<char>& moved) {
  bool any = false;
  std::vector<WrapPoint> path;
  CableKinematics kin;
  for (Cable& cable : cables) {
    if (!caughtCable(cable, bodies, knocked, jointed)) continue;
    // On a copy of the path: the cable's own kinematics are the selection's business.
    path = cable.path();
    auto stretch = [&] {
      cableLengthJacobian(path, bodies, kin);
      return kin.length - cable.restLength();
    };
    double excess = stretch();
    double compliance = lengthCompliance(kin, bodies);
    if (!(compliance > 0)) continue;
    if (excess <= kContactStretch) continue;
    // Back onto the rest length along M^-1 J^T (the least mass-weighted move that does it).
    for (int k = 0; k < kProjections && excess > kLengthSlop && compliance > 0; ++k) {
      moveAlong(kin, bodies, excess / compliance, false, moved);
      excess = stretch();
      compliance = lengthCompliance(kin, bodies);
    }
    any = true;
    // The rate out along the cable is taken off: the catch the solve would have made.
    double rate = 0;
    for (const BodyJacobian& e : kin.jacobian) {
      const BodyState& b = bodies[e.body];
      rate += e.d.head<2>().dot(b.velocity) + e.d.z() * b.angularVelocity;
    }
    if (rate > 0 && compliance > 0) moveAlong(kin, bodies, rate / compliance, true, moved);
  }
  return any;
}

}  // namespace cablelab
