// Joint velocities carried onto the new pose (joint_energy.h).
#include "engine/dynamics/joint_energy.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/dynamics/disjoint_sets.h"

namespace cablelab {

void JointEnergy::keep(std::span<const JointFrame> joints, std::vector<BodyState>& bodies,
                       std::vector<int>& changed) {
  changed.clear();
  if (joints.empty()) return;
  // Every dynamic body on a joint is a dof (3 each: x, y, angle).
  dofOfBody_.assign(bodies.size(), -1);
  bodyOfDof_.clear();
  if (jointIndex_.size() != joints.size()) {  // every joint: the world's are one island
    jointIndex_.resize(joints.size());
    std::iota(jointIndex_.begin(), jointIndex_.end(), 0);
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    for (int b : {joints[j].bodyA, joints[j].bodyB})
      if (b >= 0 && dofOfBody_[b] < 0 && moves(bodies[b])) {
        dofOfBody_[b] = 3 * static_cast<int>(bodyOfDof_.size());
        bodyOfDof_.push_back(b);
      }
  }
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(bodyOfDof_.size());
  if (n == 0) return;
  invM_.resize(n);
  v_.resize(n);
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const BodyState& b = bodies[bodyOfDof_[k]];
    invM_.segment<3>(3 * k) = Vec3(b.invMass, b.invMass, b.invInertia);
    v_.segment<3>(3 * k) = Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity);
  }
  if (!tree_.build(joints, jointIndex_, bodies, dofOfBody_, invM_)) return;
  tree_.reproject(v_);
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    BodyState& b = bodies[bodyOfDof_[k]];
    b.velocity = v_.segment<2>(3 * k);
    b.angularVelocity = v_[3 * k + 2];
    changed.push_back(bodyOfDof_[k]);
  }
}

void JointEnergy::remember(std::span<const BodyState> bodies) {
  start_.assign(bodies.begin(), bodies.end());
}

// A group of jointed bodies on which only gravity and its joints act keeps kinetic plus gravity's
// energy over the step: the velocities are scaled to the kinetic energy that leaves (a pendulum
// under Box2D's integration swings by about omega h / 2 of its energy: 2.5% for a square on a
// 1 m arm at 60 Hz, and a square swinging in and out of an elastic band, whose taut steps keep
// their energy, locked a different part of that swing in at each catch: +3.9 J of its 4.4 J
// largest kinetic energy in ten minutes). At the end of a swing the step may leave it at rest
// where the energy says it still moves, higher than it can get (a square: 0.0073 J short, lost
// at every turn if left): where the factor would be more than 1e4, or the pose is higher than the
// energy allows, the velocities stay as they are and the group is owed the difference at its
// next step, if that starts where this one left it.
namespace {
constexpr double kMaxSwingScale2 = 1e8;   // the factor's square
constexpr double kSwingStateSlop = 1e-6;  // m, rad, m/s, rad/s: Box2D's float round trip
bool swingStateKept(const BodyState& a, const BodyState& b) {
  return (a.position - b.position).norm() < kSwingStateSlop &&
         std::abs(a.angle - b.angle) < kSwingStateSlop &&
         (a.velocity - b.velocity).norm() < kSwingStateSlop * (1 + a.velocity.norm()) &&
         std::abs(a.angularVelocity - b.angularVelocity) <
             kSwingStateSlop * (1 + std::abs(a.angularVelocity));
}
}  // namespace

void JointEnergy::keepSwingEnergy(std::span<const JointFrame> joints,
                                  std::vector<BodyState>& bodies, std::vector<int>& changed,
                                  std::span<const char> swinging, const Vec2& gravity) {
  if (start_.size() != bodies.size()) return;
  const int n = static_cast<int>(bodies.size());
  group_.assign(n, -1);
  auto root = [&](int b) { return findRoot(group_, b); };
  for (const JointFrame& j : joints)
    for (const int b : {j.bodyA, j.bodyB})
      if (b >= 0 && moves(bodies[b]) && group_[b] < 0) group_[b] = b;
  for (const JointFrame& j : joints)
    if (j.bodyA >= 0 && j.bodyB >= 0 && group_[j.bodyA] >= 0 && group_[j.bodyB] >= 0)
      unite(group_, j.bodyA, j.bodyB);
  groupSwings_.assign(n, 1);
  startEnergy_.assign(n, 0.0);
  endPotential_.assign(n, 0.0);
  endKinetic_.assign(n, 0.0);
  for (const JointFrame& j : joints) {
    const int b = j.bodyB >= 0 && group_[j.bodyB] >= 0 ? j.bodyB : j.bodyA;
    if (b < 0 || group_[b] < 0) continue;
    // A limit stops its joint inelastically; a body the joint hangs from that moves on its own
    // (kinematic) does work on the group.
    const int other = b == j.bodyB ? j.bodyA : j.bodyB;
    if (j.limited || (other >= 0 && group_[other] < 0 && driven(bodies[other])))
      groupSwings_[root(b)] = 0;
  }
  const bool owes =
      owed_.size() == static_cast<size_t>(n) && left_.size() == static_cast<size_t>(n);
  groupOwed_.assign(n, 1);  // the group starts where the last step left it, owed something
  for (int b = 0; b < n; ++b) {
    if (group_[b] < 0) continue;
    const int r = root(b);
    groupSwings_[r] &= swinging[b];
    groupOwed_[r] &= owes && swingStateKept(start_[b], left_[b]);
    startEnergy_[r] += kineticEnergy(start_[b]) + gravityEnergy(start_[b], gravity);
    endPotential_[r] += gravityEnergy(bodies[b], gravity);
    endKinetic_[r] += kineticEnergy(bodies[b]);
  }
  for (int b = 0; b < n; ++b)
    if (group_[b] >= 0 && groupOwed_[root(b)] && b == root(b)) startEnergy_[b] += owed_[b];
  owed_.assign(n, 0.0);
  for (int b = 0; b < n; ++b) {
    if (group_[b] < 0) continue;
    const int r = root(b);
    const double target = startEnergy_[r] - endPotential_[r];
    if (!groupSwings_[r]) continue;
    if (!(target > 0) || !(target < kMaxSwingScale2 * endKinetic_[r])) {
      owed_[r] = target - endKinetic_[r];
      continue;
    }
    const double scale = std::sqrt(target / endKinetic_[r]);
    bodies[b].velocity *= scale;
    bodies[b].angularVelocity *= scale;
    if (std::find(changed.begin(), changed.end(), b) == changed.end()) changed.push_back(b);
  }
  left_.assign(bodies.begin(), bodies.end());
}

}  // namespace cablelab
