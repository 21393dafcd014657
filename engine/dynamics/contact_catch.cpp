#include "engine/dynamics/contact_catch.h"

#include <algorithm>

#include "engine/dynamics/box2d_bridge.h"
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

// Whether a contact can get `cable` caught: rigid, of one span, on no jointed body, and on a
// moving body that `counts` (one knocked; any, to know whether to look at all).
template <class IsJointed, class Counts>
bool caughtCable(const Cable& cable, std::span<const BodyState> bodies, IsJointed isJointed,
                 Counts counts) {
  if (cable.elastic() || cable.spanCount() != 1) return false;
  bool any = false;
  for (const BodyJacobian& e : cable.kinematics().jacobian) {
    if (!moves(bodies[e.body])) continue;
    if (isJointed(e.body)) return false;
    any |= counts(e.body);
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
  const auto isJointed = [&](int body) { return jointed[body] != 0; };
  const auto isKnocked = [&](int body) { return knocked[body] != 0; };
  for (Cable& cable : cables) {
    if (!caughtCable(cable, bodies, isJointed, isKnocked)) continue;
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

// Bodies in a touching contact at the start of the step (`touching`) or after it, or that a
// contact pushed in it, count as knocked.
void catchContactStretch(Box2DBridge& b2, std::vector<Cable>& cables,
                         std::vector<BodyState>& bodies,
                         const std::vector<std::array<int, 2>>& jointBodies,
                         std::span<const char> touching) {
  // The common step does no work (and allocates nothing): no cable a contact could get caught,
  // or no contact before, in or after the step.
  const std::span<const Vec3> impulses = b2.contactImpulses();
  auto set = [](char c) { return c != 0; };
  auto pushed = [](const Vec3& impulse) { return !impulse.isZero(); };
  const auto isJointed = [&](int body) {
    return std::any_of(jointBodies.begin(), jointBodies.end(), [body](const std::array<int, 2>& j) {
      return j[0] == body || j[1] == body;
    });
  };
  const auto anyBody = [](int) { return true; };
  if (std::none_of(cables.begin(), cables.end(),
                   [&](const Cable& c) { return caughtCable(c, bodies, isJointed, anyBody); }))
    return;
  if (std::none_of(touching.begin(), touching.end(), set) &&
      std::none_of(impulses.begin(), impulses.end(), pushed) && !b2.anyTouching())
    return;
  std::vector<char> knocked(touching.begin(), touching.end());
  knocked.resize(bodies.size(), 0);
  b2.markTouching(knocked);
  for (size_t b = 0; b < impulses.size() && b < knocked.size(); ++b)
    knocked[b] |= !impulses[b].isZero();
  if (std::none_of(knocked.begin(), knocked.end(), set)) return;
  std::vector<char> jointed(bodies.size(), 0), moved(bodies.size(), 0);
  for (const auto& [a, b] : jointBodies)
    for (const int body : {a, b})
      if (body >= 0) jointed[body] = 1;
  if (!catchCablesStretchedByContacts(cables, bodies, knocked, jointed, moved)) return;
  for (size_t b = 0; b < bodies.size(); ++b) {
    if (!moved[b]) continue;
    const BodyState& s = bodies[b];
    b2.placeBody(static_cast<int>(b), s.position, s.angle);
    b2.setVelocity(static_cast<int>(b), s.velocity, s.angularVelocity);
  }
  b2.readBodies(bodies);
}

}  // namespace cablelab
