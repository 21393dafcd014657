// World's servos (docs/servos.md): the targets the user sets, and the servos' forces a Box2D step.
#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/servo_drive.h"
#include "engine/dynamics/world.h"

namespace cablelab {

// Reached over the next step (servo_targets.h).
void World::setServoTarget(int i, double target) {
  servoTargets_.set(i, target);
  history_.add({WorldInput::Kind::ServoTarget, i, 1, {target}});
}

void World::setServoTargetAtOnce(int i, double target) {
  servoTargets_.hold(i, target);
  history_.add({WorldInput::Kind::ServoTarget, i, 0, {target}});
}

// The servos' forces over a Box2D step of dt, implicit in it (servo_drive.h), added to forces_.
void World::applyServos(double dt) {
  if (!servos_->any()) return;
  b2_->jointFrames(scene_.joints, jointBodies_, jointFrames_);
  jointCoordinates_.resize(scene_.joints.size());
  for (size_t j = 0; j < scene_.joints.size(); ++j)
    jointCoordinates_[j] = b2_->jointCoordinate(static_cast<int>(j));
  servos_->solve(jointFrames_, jointCoordinates_, bodies_, cables_, servoTargets_.targets(),
                 gravity_, dt, forces_);
}

}  // namespace cablelab
