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

// A rigid cable that pulled over the step and ends it slack: its solve pulled against a contact
// push that did not come (or came otherwise), and the pull did work on a rope going slack, which a
// rope cannot (a light polygon spinning against an anchor was thrown off at 15 m/s, +13 J in one
// step). As much of the pull is taken back as leaves the cable at its rest length, all of it at
// most: the velocity and the way the step moved the bodies with it.
bool takeBackPullIntoSlack(Cable& cable, std::span<BodyState> bodies, double dt,
                           std::vector<char>& moved) {
  const CableKinematics& kin = cable.kinematics();
  const double compliance = lengthCompliance(kin, bodies);
  if (!(compliance > 0) || !(dt > 0)) return false;
  const double pulled = cable.tension() * dt;
  const double back = std::min(pulled, -cable.stretch() / (dt * compliance));
  for (const BodyJacobian& e : kin.jacobian) {
    BodyState& b = bodies[e.body];
    const Vec2 dv = back * b.invMass * e.d.head<2>();
    const double dw = back * b.invInertia * e.d.z();
    b.velocity += dv;
    b.angularVelocity += dw;
    b.position += dt * dv;
    b.angle += dt * dw;
    moved[e.body] = 1;
  }
  cable.setTension((pulled - back) / dt);
  cable.refresh(bodies);
  return true;
}

}  // namespace

bool catchCablesStretchedByContacts(std::span<Cable> cables, std::span<BodyState> bodies,
                                    std::span<const char> knocked, std::span<const char> jointed,
                                    double dt, std::vector<char>& moved) {
  bool any = false;
  for (Cable& cable : cables) {
    if (!caughtCable(cable, bodies, knocked, jointed)) continue;
    cable.refresh(bodies);
    if (cable.stretch() < -kContactSlack && cable.tension() > 0) {
      any |= takeBackPullIntoSlack(cable, bodies, dt, moved);
      continue;
    }
    if (cable.stretch() <= kContactStretch) continue;
    // Back onto the rest length along M^-1 J^T (the least mass-weighted move that does it).
    for (int k = 0; k < kProjections && cable.stretch() > kLengthSlop; ++k) {
      const CableKinematics& kin = cable.kinematics();
      const double compliance = lengthCompliance(kin, bodies);
      if (!(compliance > 0)) break;
      const double along = cable.stretch() / compliance;
      for (const BodyJacobian& e : kin.jacobian) {
        BodyState& b = bodies[e.body];
        b.position -= along * b.invMass * e.d.head<2>();
        b.angle -= along * b.invInertia * e.d.z();
        moved[e.body] = 1;
      }
      cable.refresh(bodies);
      any = true;
    }
    // The rate out along the cable is taken off: the catch the solve would have made.
    const CableKinematics& kin = cable.kinematics();
    double rate = 0;
    for (const BodyJacobian& e : kin.jacobian) {
      const BodyState& b = bodies[e.body];
      rate += e.d.head<2>().dot(b.velocity) + e.d.z() * b.angularVelocity;
    }
    const double compliance = lengthCompliance(kin, bodies);
    if (!(rate > 0) || !(compliance > 0)) continue;
    const double impulse = rate / compliance;
    for (const BodyJacobian& e : kin.jacobian) {
      BodyState& b = bodies[e.body];
      b.velocity -= impulse * b.invMass * e.d.head<2>();
      b.angularVelocity -= impulse * b.invInertia * e.d.z();
      moved[e.body] = 1;
    }
    cable.refresh(bodies);
    any = true;
  }
  return any;
}

}  // namespace cablelab
