// Joint velocities carried onto the new pose (joint_energy.h).
#include "engine/dynamics/joint_energy.h"

#include <numeric>

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

}  // namespace cablelab
