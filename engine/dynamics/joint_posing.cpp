// setJointValues (joint_posing.h): forward kinematics over the joint trees with World's public
// calls only, so every pose it gives is one a user could have set by hand.
#include "engine/dynamics/joint_posing.h"

#include <cmath>
#include <vector>

#include "engine/core/error.h"

namespace cablelab {

namespace {

Vec2 rotated(const Vec2& v, double angle) {
  return rotate(v, std::cos(angle), std::sin(angle));
}

/// The bodies reached from `start` through joints other than `skip` (start included); false if
/// the walk reaches `stop` (a loop: the joint's two sides are joined some other way).
bool bodiesBeyond(const World& w, int start, int skip, int stop, std::vector<int>& out) {
  out.assign(1, start);
  std::vector<char> seen(w.bodyCount(), 0);
  seen[start] = 1;
  for (size_t k = 0; k < out.size(); ++k) {
    for (int j = 0; j < w.jointCount(); ++j) {
      if (j == skip) continue;
      const JointDef& d = w.scene().joints[j];
      const int a = w.findBody(d.bodyA), b = w.findBody(d.bodyB);
      const int other = a == out[k] ? b : b == out[k] ? a : -2;
      if (other == -2) continue;
      if (other == stop || other < 0) return false;  // back to A's side, or to the world
      if (!seen[other]) seen[other] = 1, out.push_back(other);
    }
  }
  return true;
}

}  // namespace

void setJointValues(World& world, std::span<const double> q, const std::string& source) {
  const int n = world.jointCount();
  if (static_cast<int>(q.size()) != n)
    throw InputError(source, "values",
                     "must have one value per joint (" + std::to_string(n) + ")" +
                         gotValue(static_cast<double>(q.size())));
  for (int j = 0; j < n; ++j)
    if (!std::isfinite(q[j]))
      throw InputError(source, "values[" + std::to_string(j) + "]",
                       "must be finite" + gotValue(q[j]));
  // From the world outwards: a joint is posed once its inner body is (the world always is). A
  // tree hanging from no body of the world keeps its first joint's body A where it is.
  std::vector<char> placed(world.bodyCount(), 0), done(n, 0);
  std::vector<int> moving;
  for (int posed = 0; posed < n;) {
    const int before = posed;
    for (int j = 0; j < n; ++j) {
      if (done[j]) continue;
      const JointDef& d = world.scene().joints[j];
      int a = world.findBody(d.bodyA), b = world.findBody(d.bodyB);
      const bool aReady = a < 0 || placed[a], bReady = b >= 0 && placed[b];
      if (!aReady && !bReady) continue;
      const double sign = aReady ? 1.0 : -1.0;  // posing A from B: the coordinate runs backwards
      if (!aReady) std::swap(a, b);
      done[j] = 1, ++posed;
      if (b < 0 || placed[b]) {
        if (b >= 0 && d.kind != JointDef::Kind::Weld &&
            std::abs(world.joint(j).value - q[j]) > 1e-9)
          throw InputError(source, "joints[" + std::to_string(j) + "]",
                           "closes a loop of joints: its value follows from the others' "
                           "(set_joint_values poses trees of joints)" +
                               gotValue(q[j]));
        continue;
      }
      if (!bodiesBeyond(world, b, j, a, moving))
        throw InputError(
            source, "joints[" + std::to_string(j) + "]",
            "is in a loop of joints (set_joint_values poses trees of joints)" + gotValue(q[j]));
      const JointState s = world.joint(j);
      const double delta = sign * (q[j] - s.value);
      for (int body : moving) {
        const BodyState& p = world.body(body);
        if (d.kind == JointDef::Kind::Revolute) {
          world.setBodyTransform(body, s.anchorB + rotated(p.position - s.anchorB, delta),
                                 p.angle + delta);
        } else if (d.kind == JointDef::Kind::Prismatic) {
          const int inner = world.findBody(d.bodyA);
          const double turned =
              inner < 0 ? 0.0 : world.body(inner).angle - world.scene().bodies[inner].angle;
          world.setBodyTransform(body, p.position + delta * rotated(d.axis, turned), p.angle);
        }
        world.setBodyVelocity(body, Vec2::Zero(), 0.0);
      }
      placed[b] = 1;
    }
    if (posed == before)
      for (int j = 0; j < n; ++j)
        if (!done[j]) {
          placed[world.findBody(world.scene().joints[j].bodyA)] = 1;
          break;
        }
  }
  world.refreshCables();
}

}  // namespace cablelab
