// World's stage after each Box2D step that carries the jointed bodies' energy onto the joints'
// new pose (joint_energy.h): the projection of the turning joints, and the free swings' energy.
#include <cmath>
#include <vector>

#include "engine/dynamics/box2d_bridge.h"
#include "engine/dynamics/joint_energy.h"
#include "engine/dynamics/world.h"

namespace cablelab {

namespace {
constexpr double kJointStillTurn = 1e-5;  // rad a step: joints that turn less keep Box2D's solve
}  // namespace

void World::keepJointEnergy(double dt) {
  if (!keepsJointEnergy_ || scene_.joints.empty()) return;
  b2_->jointFrames(scene_.joints, jointBodies_, jointFrames_);
  // Joints that turn by less than kJointStillTurn a step lose less than kJointStillTurn^2 / 2 of
  // their energy to Box2D's solve (a hand holding still): not worth the projection.
  bool turning = false;
  for (const auto& [a, b] : jointBodies_)
    for (const int body : {a, b})
      turning |= body >= 0 && std::abs(bodies_[body].angularVelocity) * dt > kJointStillTurn;
  if (turning)
    jointEnergy_->keep(jointFrames_, bodies_, reprojected_);
  else
    reprojected_.clear();
  // Bodies only gravity and their joints moved over the step (no cable, contact, servo, load,
  // damping): their groups keep their energy with gravity's (joint_energy.h), the step at the end
  // of a swing too, where the joints hardly turn.
  // Touching at the start of the step or at its end (a hull contact begun within it).
  static thread_local std::vector<char> swinging, touchingNow;  // scratch: no allocation a step
  touchingNow.assign(bodies_.size(), 0);
  b2_->markTouching(touchingNow);
  swinging.assign(bodies_.size(), 0);
  bool any = false;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    swinging[b] = !onCable_[b] && !touching_[b] && !touchingNow[b] && pendingForces_[b].isZero() &&
                  scene_.bodies[b].linearDamping == 0 && scene_.bodies[b].angularDamping == 0;
    any |= swinging[b];
  }
  for (size_t j = 0; j < scene_.joints.size(); ++j)
    if (scene_.joints[j].servo.enabled)
      for (const int body : jointBodies_[j])
        if (body >= 0) swinging[body] = 0;
  if (any) jointEnergy_->keepSwingEnergy(jointFrames_, bodies_, reprojected_, swinging, gravity_);
  for (int b : reprojected_) b2_->setVelocity(b, bodies_[b].velocity, bodies_[b].angularVelocity);
}

}  // namespace cablelab
