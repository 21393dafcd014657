// Joint limits in the cable solve (joint_limits.h).
#include "engine/dynamics/joint_limits.h"

#include <algorithm>

#include "engine/dynamics/joint_projection.h"

namespace cablelab {

void JointLimits::free(std::span<const int> island, int jointCount) {
  if (static_cast<int>(locked_.size()) < jointCount)
    locked_.resize(jointCount, 0), rate_.resize(jointCount, 0.0);
  for (int j : island) locked_[j] = 0;
}

void JointLimits::lockAt(int j, double rate) {
  if (j >= static_cast<int>(locked_.size())) locked_.resize(j + 1, 0), rate_.resize(j + 1, 0.0);
  locked_[j] = 1;
  rate_[j] = rate;
}

bool JointLimits::lockCrossing(std::span<const JointFrame> joints, std::span<const int> island,
                               std::span<const BodyState> bodies, std::span<const int> dofOfBody,
                               const Eigen::VectorXd& v1, double h) {
  bool locked = false;
  for (int j : island) {
    const JointFrame& joint = joints[j];
    if (!joint.limited || locked_[j]) continue;
    const JointRow row = coordinateRow(joint, bodies, dofOfBody);
    if (row.dof[0] < 0 && row.dof[1] < 0) continue;  // on no dof: not this island's to move
    const double rate = row.dot(v1) + row.bias;
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
