// The figure 4-5 experiment: the hand starts open about the start point, closes into a pinch
// grasp (hand_grasp.h), then the Jacobian controller (outer loop, every 0.053 s) drives the box
// to a constant or ramped target while the World simulates fingers, membranes and box (inner PD
// servos at every sub-step). The same run, stopped early once its outcome is clear, is one
// target of the simulated reach sweep (hand_reach.h).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_grasp.h"
#include "engine/hand/hand_model.h"
#include "engine/hand/hand_mpc.h"

namespace cablelab {

/// The target switches to `target` at time `t` (s): a step the controller must ride out.
struct TargetChange {
  double t = 0;
  Vec2 target = Vec2::Zero();
};

/// When a run may stop before `time` (the reach sweep; `track` runs to the end).
struct EarlyStop {
  bool enabled = false;
  double tolerance = 0.005;  ///< m: settled = within this of a target that no longer moves
  double settledFor = 1.0;   ///< s within the tolerance before stopping as reached
  double stallFor = 3.0;     ///< s without getting closer by `progress` or by `share` of the
                             ///< error before stopping as failed
  double progress = 0.0005;  ///< m
  double share = 0.05;
  double angleTolerance = 0.02;  ///< rad: a box that turns settles within this of its angle too
};

/// The outer-loop law: the Jacobian controller (hand_controller.h, the thesis's) or
/// model-predictive control (hand_mpc.h).
enum class HandLaw { Jacobian, Mpc };

struct TrackOptions {
  Vec2 target = Vec2::Zero();         ///< final target box centre (m)
  double targetAngle = 0;             ///< final target box angle (rad; the box must turn)
  std::optional<Vec2> start;          ///< box position where the hand grasps it; default
                                      ///< defaultStart(target)
  double rampTime = 0;                ///< s; > 0: the target moves linearly from the start to
                                      ///< `target` over this long, starting at grasp time
  std::vector<TargetChange> changes;  ///< later target steps, in time order
  double time = 15;                   ///< simulated time (s)
  bool pid = false;                   ///< add the integral term (k_i = kHandPidKi)
  GraspOptions grasp;
  HandControllerParams controller;  ///< outer-loop gains (`pid` sets ki = kHandPidKi)
  HandLaw law = HandLaw::Jacobian;
  HandMpcParams mpc;  ///< the law's horizon and weights when it is HandLaw::Mpc
  EarlyStop stop;
};

struct TrackSample {
  double t = 0;                   ///< s
  Vec2 target = Vec2::Zero();     ///< m
  Vec2 box = Vec2::Zero();        ///< m
  double tension = 0;             ///< the larger membrane tension (N)
  Vec2 reference = Vec2::Zero();  ///< the controller's reference r (m); the box before control
  double targetAngle = 0;         ///< rad
  double angle = 0;               ///< the box's angle (rad)
};

struct TrackResult {
  double finalError = 0;       ///< |box - target| at the end (m)
  double rmsError = 0;         ///< RMS of |box - target| over the steps after control began (m)
  double finalAngleError = 0;  ///< |box angle - target angle| at the end (rad)
  double rmsAngleError = 0;    ///< its RMS over the steps after control began (rad)
  double graspTime = -1;       ///< s; -1 if the membranes never both wrapped the box
  double startError = 0;       ///< |box - target| when control began (m)
  bool graspHeld = false;      ///< the grasp closed and was never lost afterwards
  int losses = 0;              ///< times the box was lost (each followed by a re-grasp attempt)
  double startTension = 0;     ///< the larger membrane tension when control began (N): the squeeze
  double maxTension = 0;       ///< the larger membrane tension's maximum after control began (N)
  bool stoppedEarly = false;
  bool reached = false;       ///< ended within the early-stop tolerance(s) (any run)
  Vec2 start = Vec2::Zero();  ///< where the grasp closed about (m)
  HandJoints finalJoints = HandJoints::Zero();
  std::vector<GraspEvent> events;
  std::vector<TrackSample> samples;  ///< one per step, t = 0 first
  /// s from control's start until the box came within 5 mm of the target and stayed there to
  /// the end; -1 if it ended farther.
  double timeTo5mm = -1;
  double overshoot = 0;       ///< m: furthest the box went past the target, along start -> target
  int limitHits = 0;          ///< times a joint came within 1 mrad (1 mm) of a limit under control
  double solveMicros = 0;     ///< mean wall time of one outer-loop update (us)
  double maxSolveMicros = 0;  ///< the longest one (us)
};

/// The default start: the pinch at the origin, or (0.1, 0.1) m when the target is within 5 cm
/// of it, so that the box never starts on the target.
Vec2 defaultStart(const Vec2& target);

/// Runs the experiment; `onStep(done, total)` is called after every step (may be empty).
/// Throws SimulationError if the simulation blows up.
TrackResult runTracking(const TrackOptions& options, const HandModel& model = {},
                        const std::function<void(long, long)>& onStep = {});

}  // namespace cablelab
