// Servo targets reached over a step (servo_targets.h).
#include "engine/dynamics/servo_targets.h"

namespace cablelab {

void ServoTargets::reset(std::span<const JointDef> joints) {
  set_.clear(), speeds_.clear();
  for (const JointDef& joint : joints)
    set_.push_back(joint.servo.target), speeds_.push_back(joint.servo.speed);
  from_ = now_ = set_;
  jumped_ = false;
}

void ServoTargets::beginSubstep(int s, int n) {
  if (s == 0 && jumped_) from_ = set_;
  if (s == 0) jumped_ = false;
  // The last sub-step ends on the target set, to the bit (one sub-step: as a jump always did).
  const double share = static_cast<double>(s + 1) / n;
  now_.resize(set_.size());
  for (size_t j = 0; j < set_.size(); ++j)
    now_[j] = s + 1 >= n ? set_[j] : from_[j] + (set_[j] - from_[j]) * share;
}

void ServoTargets::moveOn(double taken) {
  for (size_t j = 0; j < set_.size(); ++j) {
    set_[j] += speeds_[j] * taken;
    from_[j] += speeds_[j] * taken;
    now_[j] += speeds_[j] * taken;
  }
}

}  // namespace cablelab
