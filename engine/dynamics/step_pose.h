// Where Box2D leaves a body after a step: the pose the cable solves predict their end-of-step
// lengths at. Private to engine/dynamics.
#pragma once

#include <cmath>

#include <span>
#include <vector>

#include "engine/cable/cable.h"
#include "engine/core/math.h"
#include "engine/dynamics/box2d_bridge.h"

namespace cablelab {

/// How a body moves over a step: in a straight line (free), turned about the point its velocity
/// leaves at rest (jointed), or turned about a fixed pivot (a link hung from a body that does not
/// move by its one revolute joint: `anchor` that body's anchor point, `arm` the link's own anchor
/// point less its origin at the start of the step).
struct StepMotion {
  enum class Kind { Free, Jointed, Pivoted };
  Kind kind = Kind::Free;
  Vec2 anchor = Vec2::Zero(), arm = Vec2::Zero();
  int joint = -1;  ///< the one joint it is on (stepMotions; -2: several)
};

/// The pose after a step of h from s at velocity v = (vx, vy, omega), into p (its velocity too).
/// A free body goes in a straight line, as Box2D integrates it. A jointed one ends where the
/// joints' position correction puts it: turned by h omega, with its velocity turned alike.
/// Carried along its tangent instead, a pulley at arm r on a swinging link would land
/// h^2 omega^2 r / 2 outside its circle, and the cable would hold its length at a place the
/// pulley never reaches (a pendulum carrying a pulley stretched its rigid cable 1.3 mm and lost a
/// tenth of its energy a minute at 60 Hz). A pivoted link ends with its anchor on the pivot.
inline void stepPose(const BodyState& s, const Vec3& v, double h, const StepMotion& motion,
                     BodyState& p) {
  const double a = h * v[2];
  p.angle = s.angle + a;
  p.angularVelocity = v[2];
  switch (motion.kind) {
    case StepMotion::Kind::Free:
      p.velocity = v.head<2>();
      p.position = s.position + h * p.velocity;
      return;
    case StepMotion::Kind::Pivoted:
      p.position = motion.anchor - rotate(motion.arm, a);
      p.velocity = v[2] * perp(p.position - motion.anchor);
      return;
    case StepMotion::Kind::Jointed: {
      // x1 - x0 = (R(a) - I) (x0 - c), c = x0 + perp(v) / omega the point at rest.
      // One cos and sin of the turn serve the turned velocity and sin(a) / a alike (Newton asks
      // for this pose at every iteration).
      double cosA, sinA;
      cosSin(a, cosA, sinA);
      auto sinc = [](double x, double sinX) {
        return std::abs(x) < 1e-4 ? 1 - x * x / 6 : sinX / x;
      };
      const double halfA = 0.5 * a;
      const double half = sinc(halfA, std::abs(halfA) < 1e-4 ? 0.0 : std::sin(halfA));
      const double along = h * sinc(a, sinA), across = -0.5 * h * a * half * half;
      p.position = s.position + Vec2(along * v[0] + across * v[1], along * v[1] - across * v[0]);
      p.velocity = rotate(v.head<2>(), cosA, sinA);
      return;
    }
  }
}

/// Whether World puts a body that moved this way at its predicted pose after Box2D's step: a
/// pivoted link that touches nothing (contacts need Box2D's correction; `touching` empty: none).
inline bool placedAfterStep(const StepMotion& motion, std::span<const char> touching, int body) {
  return motion.kind == StepMotion::Kind::Pivoted && (touching.empty() || !touching[body]);
}

/// How each dof body moves (`motions`, one per dof body; `dofOfBody`: body -> first dof, -1 if
/// none): from the joints among `joints` (indices `island`) it is on. Pivoted: on exactly one,
/// as its body B, a revolute joint without limits whose body A does not move (a limit is Box2D's
/// to hold: placed past it, an arm that a rope pulled against its -0.5 rad stop swung to -1.8).
inline void stepMotions(std::span<const JointFrame> joints, std::span<const int> island,
                        std::span<const BodyState> bodies, std::span<const int> dofOfBody,
                        std::vector<StepMotion>& motions) {
  for (StepMotion& m : motions) m = StepMotion{};
  for (int j : island)
    for (const int b : {joints[j].bodyA, joints[j].bodyB})
      if (b >= 0 && dofOfBody[b] >= 0) {
        StepMotion& m = motions[dofOfBody[b] / 3];
        m.joint = m.kind == StepMotion::Kind::Free ? j : -2;
        m.kind = StepMotion::Kind::Jointed;
      }
  for (int j : island) {
    const JointFrame& joint = joints[j];
    const int a = joint.bodyA, b = joint.bodyB;
    if (joint.kind != JointDef::Kind::Revolute || joint.limited || b < 0 || dofOfBody[b] < 0)
      continue;
    StepMotion& m = motions[dofOfBody[b] / 3];
    const bool still = a < 0 || (!moves(bodies[a]) && bodies[a].velocity.isZero() &&
                                 bodies[a].angularVelocity == 0);
    if (m.joint == j && still)
      m = {StepMotion::Kind::Pivoted, joint.anchorA, joint.anchor - bodies[b].position, j};
  }
}

}  // namespace cablelab
