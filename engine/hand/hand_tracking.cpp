#include "engine/hand/hand_tracking.h"

#include <cmath>

#include "engine/core/error.h"
#include "engine/hand/hand_kinematics.h"
#include "engine/dynamics/world.h"

namespace cablelab {

namespace {
constexpr double kSqueezeSettle = 0.5;  // s after the closing ramp before the outer loop starts
}  // namespace

HandJoints readHandJoints(const World& world) {
  HandJoints q;
  for (int j = 0; j < 6; ++j) q[j] = world.joint(world.findJoint(kHandJointNames[j])).value;
  return q;
}

void placeHand(World& world, const HandModel& model, const HandJoints& q) {
  const char* fingers[2] = {"top", "bottom"};
  for (int f = 0; f < 2; ++f) {
    const FingerPose pose = fingerPose(model, q, f);
    const std::string name = fingers[f];
    const std::pair<std::string, std::pair<Vec2, double>> bodies[3] = {
        {name + "_link", {pose.link, pose.linkAngle}},
        {name + "_slider", {pose.slider, pose.sliderAngle}},
        {name + "_paddle", {pose.paddle, pose.paddleAngle}}};
    for (const auto& [body, placement] : bodies) {
      const int i = world.findBody(body);
      world.setBodyTransform(i, placement.first, placement.second);
      world.setBodyVelocity(i, Vec2::Zero(), 0);
    }
  }
  for (int j = 0; j < 6; ++j) world.setServoTarget(world.findJoint(kHandJointNames[j]), q[j]);
}

TrackResult runTracking(const TrackOptions& o, const HandModel& model,
                        const std::function<void(long, long)>& onStep) {
  World world(buildHandScene(model), "hand");
  const double dt = world.scene().dt;
  const int substeps = world.scene().substeps;
  const long steps = std::lround(o.time / dt);
  const int box = world.findBody(kHandBoxName);
  const int cables[2] = {world.findCable(kHandCableNames[0]), world.findCable(kHandCableNames[1])};

  HandControllerParams params = o.controller;
  if (o.pid) params.ki = kHandPidKi;

  HandController controller(model, params);

  const HandJoints open = model.openPose();
  placeHand(world, model, open);
  HandJoints offset = HandJoints::Zero();  // the controller's accumulated joint-target change
  auto targetAt = [&](double t, double graspTime) -> Vec2 {
    if (o.rampTime <= 0) return o.target;
    if (graspTime < 0) return Vec2::Zero();
    return o.target * std::clamp((t - graspTime) / o.rampTime, 0.0, 1.0);
  };

  TrackResult result;
  result.samples.reserve(steps + 1);
  result.samples.push_back({0, targetAt(0, -1), world.body(box).position});
  double nextUpdate = -1, sumSquares = 0;
  long controlledSteps = 0;
  for (long s = 0; s < steps; ++s) {
    const double t = world.time();
    // Closing ramp from the open pose to the pinch pose, plus the controller's offsets.
    const HandJoints nominal = open * std::max(0.0, 1 - t / o.closeTime);
    if (result.graspTime >= 0 && t >= nextUpdate - 1e-9) {
      const BodyState& b = world.body(box);
      offset += controller.update(readHandJoints(world), b.position, targetAt(t, result.graspTime),
                                  model.clamp(nominal + offset));
      nextUpdate += params.period;
    }
    const HandJoints commanded = model.clamp(nominal + offset);
    offset = commanded - nominal;  // no wind-up against the limits
    for (int j = 0; j < 6; ++j) world.setServoTarget(j, commanded[j]);

    world.step(dt, substeps);
    if (result.graspTime < 0 && world.cable(cables[0]).wraps() >= 2 &&
        world.cable(cables[1]).wraps() >= 2) {
      result.graspTime = world.time();
      // Control begins once the closing ramp has finished and the squeeze has settled a little
      // (before that the membranes barely press and the statics model is ill-conditioned).
      nextUpdate = std::max(world.time(), o.closeTime + kSqueezeSettle);
    }
    const Vec2 target = targetAt(world.time(), result.graspTime);
    const Vec2 position = world.body(box).position;
    result.samples.push_back({world.time(), target, position});
    if (result.graspTime >= 0) {
      sumSquares += (position - target).squaredNorm();
      ++controlledSteps;
    }
    if (onStep) onStep(s + 1, steps);
  }
  const TrackSample& last = result.samples.back();
  result.finalError = (last.box - last.target).norm();
  result.rmsError =
      controlledSteps > 0 ? std::sqrt(sumSquares / controlledSteps) : result.finalError;
  return result;
}

}  // namespace cablelab
