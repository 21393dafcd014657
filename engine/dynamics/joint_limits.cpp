// Joint limits in the cable solve (joint_limits.h).
#include "engine/dynamics/joint_limits.h"

#include <algorithm>

#include "engine/core/math.h"

namespace cablelab {

void JointLimits::free(std::span<const int> island, int jointCount) {
  if (static_cast<int>(locked_.size()) < jointCount)
    locked_.resize(jointCount, 0), rate_.resize(jointCount, 0.0);
  for (int j : island) {
    lockedCount_ -= locked_[j];
    locked_[j] = 0;
  }
}

void JointLimits::lockAt(int j, double rate) {
  if (j >= static_cast<int>(locked_.size())) locked_.resize(j + 1, 0), rate_.resize(j + 1, 0.0);
  lockedCount_ += !locked_[j];
  locked_[j] = 1;
  rate_[j] = rate;
}

namespace {

// A body's velocity (vx, vy, omega): v's entries for a dof, else its own (the world: at rest).
Vec3 velocityOf(int body, std::span<const BodyState> bodies, std::span<const int> dofOfBody,
                const Eigen::VectorXd& v) {
  if (body < 0) return Vec3::Zero();
  if (const int d = dofOfBody[body]; d >= 0) return v.segment<3>(d);
  const BodyState& s = bodies[body];
  return Vec3(s.velocity.x(), s.velocity.y(), s.angularVelocity);
}

// The rate of a revolute or prismatic joint's coordinate: coordinateRow(joint) . v + bias with the
// few terms it has written out. It runs for every limited joint every sub-step, and through the
// row (which also fills its coefficients and bias) the hand's step cost 1.7k instructions more.
double coordinateRate(const JointFrame& joint, std::span<const BodyState> bodies,
                      std::span<const int> dofOfBody, const Eigen::VectorXd& v) {
  const Vec3 a = velocityOf(joint.bodyA, bodies, dofOfBody, v);
  const Vec3 b = velocityOf(joint.bodyB, bodies, dofOfBody, v);
  if (joint.kind != JointDef::Kind::Prismatic) return b[2] - a[2];
  auto pointVelocity = [&](int body, const Vec3& u) {
    if (body < 0) return Vec2(Vec2::Zero());
    return Vec2(u.head<2>() + u[2] * perp(Vec2(joint.anchor - bodies[body].position)));
  };
  return joint.axis.dot(pointVelocity(joint.bodyB, b) - pointVelocity(joint.bodyA, a));
}

}  // namespace

bool JointLimits::lockCrossing(std::span<const JointFrame> joints, std::span<const int> island,
                               std::span<const BodyState> bodies, std::span<const int> dofOfBody,
                               const Eigen::VectorXd& v1, double h) {
  bool locked = false;
  for (int j : island) {
    const JointFrame& joint = joints[j];
    if (!joint.limited || locked_[j]) continue;
    const auto moves = [&](int body) { return body >= 0 && dofOfBody[body] >= 0; };
    if (!moves(joint.bodyA) && !moves(joint.bodyB)) continue;  // not this island's to move
    const double rate = coordinateRate(joint, bodies, dofOfBody, v1);
    // The rates that reach each bound within h (0 once past it: Box2D's position correction
    // brings the joint back).
    const double down = -std::max(joint.value - joint.lower, 0.0) / h;
    const double up = std::max(joint.upper - joint.value, 0.0) / h;
    // Rounding of a rate held at its bound by the last solve is not a crossing.
    const double slack = 1e-9 * (1 + std::abs(rate));
    if (rate < down - slack || rate > up + slack) {
      lockAt(j, rate < down ? down : up);
      locked = true;
    }
  }
  return locked;
}

}  // namespace cablelab
