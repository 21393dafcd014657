// The hand's grasp sequence, the one `cablelab track`, `cablelab reach` and the sandbox run:
//
//   Opening   (re-grasp only) servo targets ramp from where the fingers are to the open pose
//             about the box, over `openTime`;
//   Closing   from the open pose about the start point (fingers swung apart, membranes clear of
//             the box) the targets ramp to the rigid pinch there over `closeTime`; the grasp has
//             closed once both membranes wrap the box (two wrap points each);
//   Control   from `settleTime` after the closing ramp, the Jacobian controller's updates, each
//             spread linearly over one outer period so the servo targets move without steps
//             (a step makes the paddles jump and the membranes' damping spike the tension);
//   Lost      a membrane unwrapped (no wrap point) or went slack after the grasp closed: the
//             fingers stop where they are for `stopTime`, then the hand re-grasps about the
//             box (Opening), at most `maxRegrasps` times; then Failed (held still).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_model.h"

namespace cablelab {

class World;

struct GraspOptions {
  double openTime = 0.5;    ///< s to swing open before a re-grasp
  double closeTime = 1.0;   ///< s to swing from the open pose to the pinch
  double settleTime = 0.5;  ///< s after the closing ramp before the outer loop starts
  double stopTime = 0.2;    ///< s held still after losing the box, before re-grasping
  int maxRegrasps = 2;
};

/// Something the sequence did, with the world time it happened (s).
struct GraspEvent {
  double t = 0;
  std::string what;  ///< "grasp closed", "top membrane unwrapped", "re-grasp", ...
};

/// An outer-loop law in place of the Jacobian controller (a custom controller, e.g. written in
/// Python): from the measured joints q, the box centre (m) and the joint targets commanded now,
/// the joint-target increment (rad, m) of one update.
using GraspLaw =
    std::function<HandJoints(const HandJoints& q, const Vec2& box, const HandJoints& commanded)>;

class HandGrasp {
 public:
  enum class Phase { Opening, Closing, Control, Lost, Failed };

  HandGrasp(const HandModel& model, const HandControllerParams& params, GraspOptions options = {});

  /// Finds the hand's joints, box and membranes in `world`; false if it is not a hand scene.
  bool attach(const World& world);

  /// Teleports the box to `start` (at rest) and the fingers to the open pose about it, and
  /// starts closing. The start must be one the fingers can pinch (pinchWithinLimits).
  void begin(World& world, const Vec2& start);
  /// The world already pinches the box at its current joints (the hand scene as built): the
  /// grasp counts as closed now and control starts after the settle time.
  void beginPinched(const World& world);

  /// Before World::step: runs the outer loop when due and sets the servo targets. The update is
  /// `law`'s when given, else the controller's towards `target` (neither: the hand holds); it is
  /// clamped into the joint limits and spread over one period either way.
  void beforeStep(World& world, const std::optional<Vec2>& target, const GraspLaw& law = {});
  /// After World::step: notices the grasp closing and a lost grasp.
  void afterStep(const World& world);
  /// The box angle (rad) the controller turns the box to when the box may turn (HandModel::turn).
  void setTargetAngle(double angle) { targetAngle_ = angle; }

  Phase phase() const { return phase_; }
  double graspTime() const { return graspTime_; }        ///< s; -1 until the grasp first closes
  double controlStart() const { return controlStart_; }  ///< s; +inf until known
  bool controlling(double t) const { return phase_ == Phase::Control && t >= controlStart_ - 1e-9; }
  /// False once the box was lost after the grasp had closed (even if re-grasped since).
  bool held() const { return losses_ == 0; }
  int losses() const { return losses_; }
  int updates() const { return updates_; }
  const std::vector<GraspEvent>& events() const { return events_; }
  const HandJoints& commanded() const { return commanded_; }  ///< latest joint targets
  HandController& controller() { return controller_; }
  const HandController& controller() const { return controller_; }
  int boxBody() const { return box_; }
  int membrane(int finger) const { return cables_[finger]; }
  /// Joint values of the hand's actuated joints in `world`, in HandJoints order.
  HandJoints joints(const World& world) const;

 private:
  void startRamp(double t, const HandJoints& from, const HandJoints& to, double duration);
  void setServos(World& world, const HandJoints& q) const;
  std::string lossReason(const World& world) const;

  HandModel model_;
  GraspOptions options_;
  HandController controller_;
  std::array<int, 6> joints_{};
  int box_ = -1;
  std::array<int, 2> cables_{-1, -1};
  Phase phase_ = Phase::Closing;
  bool closed_ = false;  ///< both membranes wrap the box (this grasp)
  double graspTime_ = -1, controlStart_ = 0, nextUpdate_ = 0, phaseStart_ = 0;
  int losses_ = 0, regrasps_ = 0, updates_ = 0;
  // Servo targets ramp from rampFrom_ to commanded_ between rampStart_ and rampEnd_.
  HandJoints rampFrom_ = HandJoints::Zero(), commanded_ = HandJoints::Zero();
  double rampStart_ = 0, rampEnd_ = 0;
  Vec2 pinchAt_ = Vec2::Zero();
  double targetAngle_ = 0;
  std::vector<GraspEvent> events_;
};

/// Joint values of the hand scene's actuated joints, in HandJoints order.
HandJoints readHandJoints(const World& world);

/// Moves the finger bodies of a hand-scene World to joints q (teleport, velocities zeroed) and
/// sets the servo targets to q.
void placeHand(World& world, const HandModel& model, const HandJoints& q);

/// The pinch centre nearest to `g` that the fingers can reach (g itself when they can).
Vec2 nearestPinch(const HandModel& model, const Vec2& g);

}  // namespace cablelab
