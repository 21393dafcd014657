// The figure 4-5 experiment: the hand starts open, closes into a pinch grasp, then the Jacobian
// controller (outer loop, every 0.053 s) drives the box to a constant or ramped target while the
// World simulates fingers, membranes and box (inner PD servos at every sub-step).
//
// Start sequence: the hand scene is built at the pinch pose; the fingers are placed at
// HandModel::openPose() (membranes clear of the box) and their servo targets ramp to the pinch
// pose over `closeTime`. grasp_time is the first step at which both membranes wrap the box (two
// wrap points each); control begins at the next outer-loop tick. The closing ramp keeps running
// underneath the controller's accumulated joint offsets, so the squeeze finishes as planned.
#pragma once

#include <functional>
#include <vector>

#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_model.h"

namespace cablelab {

struct TrackOptions {
  Vec2 target = Vec2::Zero();       ///< final target box centre (m)
  double rampTime = 0;              ///< s; > 0: the target moves linearly from (0, 0) to `target`
                                    ///< over this long, starting at grasp time; 0: constant target
  double time = 15;                 ///< simulated time (s)
  bool pid = false;                 ///< add the integral term (k_i = kHandPidKi)
  double closeTime = 1.0;           ///< s to swing from the open pose to the pinch pose
  HandControllerParams controller;  ///< outer-loop gains (`pid` sets ki = kHandPidKi)
};

struct TrackSample {
  double t = 0;                ///< s
  Vec2 target = Vec2::Zero();  ///< m
  Vec2 box = Vec2::Zero();     ///< m
};

struct TrackResult {
  double finalError = 0;             ///< |box - target| at the end (m)
  double rmsError = 0;               ///< RMS of |box - target| over the steps after the grasp (m)
  double graspTime = -1;             ///< s; -1 if the membranes never both wrapped the box
  std::vector<TrackSample> samples;  ///< one per step, t = 0 first
};

/// Runs the experiment; `onStep(done, total)` is called after every step (may be empty).
/// Throws SimulationError if the simulation blows up.
TrackResult runTracking(const TrackOptions& options, const HandModel& model = {},
                        const std::function<void(long, long)>& onStep = {});

/// Joint values of the hand scene's actuated joints, in HandJoints order.
class World;
HandJoints readHandJoints(const World& world);

/// Moves the finger bodies of a hand-scene World to joints q (teleport, velocities zeroed) and
/// sets the servo targets to q.
void placeHand(World& world, const HandModel& model, const HandJoints& q);

}  // namespace cablelab
