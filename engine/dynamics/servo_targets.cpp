// Servo targets reached over a step (servo_targets.h).
#include "engine/dynamics/servo_targets.h"

namespace cablelab {

void ServoTargets::reset(std::span<const JointDef> joints, std::span<const double> start) {
  set_.clear(), speeds_.clear();
  for (const JointDef& joint : joints)
    set_.push_back(joint.servo.target), speeds_.push_back(joint.servo.speed);
  from_ = now_ = set_;
  // A target the scene steps its joint to is reached over the first step, as one set before it:
  // in one jump, a stiff servo reached it within the first sub-step, n sub-steps throwing what
  // it lifted n times as fast as one (docs/servos.md, "Targets set between steps").
  if (start.size() == set_.size()) from_.assign(start.begin(), start.end());
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
