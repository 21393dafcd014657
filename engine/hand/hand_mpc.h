// Model-predictive control of the hand (docs/control.md#model-predictive-control): a
// receding-horizon alternative to the Jacobian controller (hand_controller.h), on the same
// quasi-static model.
//
// Every outer-loop update (period T) it plans the joint-target increments of the next N updates,
// u = (dq_1, ..., dq_N) (6N), and applies the first:
//   * the model, linearised at the measured joints q and box b: the statics equilibrium
//     e(q') = e(q) + J (q' - q) + d (J = de/dq, d the model's offset, re-estimated while the box
//     rests), the joints following their targets through the servos' lag plus their static droop,
//     the box following e with its mass, the table's drag and the membranes' stiffness K. All
//     linear, so every predicted state is an affine map of u (MpcPrediction);
//   * the cost: the box's distance to the target at every step, its speed at the horizon's end,
//     the paddles' gap off the pinch's and their tilt off face-on, and a small effort term;
//   * a box that turns (HandModel::turn): its angle follows the statics' equilibrium angle at the
//     predicted joints (plus its own offset), costs its distance to the target angle (in metres
//     at the corners, angleArm per radian), and the gap and the face-on tilt turn with it;
//   * the constraints, what the Jacobian controller only reacts to: joint limits (targets and
//     predicted joints), joint rate limits, every face-on condition at the predicted box (both
//     membranes keep wrapping it face-on, with a margin) and membrane tension bounds.
// The QP (6N variables, about 50N rows) is solved by the project's active-set solver
// (engine/core/small_qp.h), warm-started from the last plan shifted by one step.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_kinematics.h"
#include "engine/hand/hand_model.h"

namespace cablelab {

struct HandMpcParams {
  int horizon = 6;             ///< N: updates planned ahead
  double period = 0.053;       ///< s: the outer loop's (as the Jacobian controller's)
  double effort = 1e-2;        ///< cost of a joint increment, m^2 of box error per rad^2 (or m^2)
  double gapWeight = 4.0;      ///< the paddles' gap off the pinch's (per m of box error)
  double tiltWeight = 0.01;    ///< m^2 per rad^2: a paddle's tilt off face-on
  double settleWeight = 0.02;  ///< s^2: the box's speed at the horizon's end
  double wrapMargin = 0.02;    ///< m: every face-on condition keeps this much slack
  double minTension = 20;      ///< N: each membrane stays at least this taut
  double maxTension = 150;     ///< N
  double maxSpeed = 0.5;       ///< m/s: the box's predicted speed along x and along y
  double revoluteRate = 1.0;   ///< rad/s: fastest a revolute joint's target moves
  double slideRate = 0.5;      ///< m/s: fastest a slide's target moves
  double limitMargin = 0.01;   ///< rad or m: predicted joints stay this far inside their limits
  double restSpeed = 0.02;     ///< m/s: below it the model's offset d is re-estimated
  double offsetGain = 0.3;     ///< per update: share of the offset's change taken
  /// Active-set iterations per update at most: the solver's iterates stay feasible, so a plan
  /// cut short still meets every constraint; this bounds the worst update's time.
  int maxIterations = 60;
  double angleArm = 0.25;  ///< m per rad: the angle's error counts as its corners' motion
};

/// The model at the measured state, what the plan is linear in.
struct MpcLinearisation {
  HandJoints joints = HandJoints::Zero();      ///< measured q (rad, m)
  HandJoints droop = HandJoints::Zero();       ///< q minus the servos' lagged targets (rad, m)
  Vec2 box = Vec2::Zero();                     ///< measured box centre (m)
  Vec2 velocity = Vec2::Zero();                ///< measured box velocity (m/s)
  Vec2 equilibrium = Vec2::Zero();             ///< e(q) + d (m)
  BoxJacobian jacobian = BoxJacobian::Zero();  ///< de/dq (2 x 6)
  Eigen::Matrix2d stiffness = Eigen::Matrix2d::Zero();  ///< K (N/m)
  FingertipJacobian tips = FingertipJacobian::Zero();   ///< d fingertips/dq (8 x 6)
  FaceOnTerms faceOn;                                   ///< at the measured fingertips and box
  Eigen::Vector2d tension = Eigen::Vector2d::Zero();    ///< membranes' tensions (N)
  Eigen::Matrix<double, 2, 6> tensionJoints = Eigen::Matrix<double, 2, 6>::Zero();  ///< dT/dq
  Eigen::Matrix2d tensionBox = Eigen::Matrix2d::Zero();                             ///< dT/db (N/m)
  // A box that turns (all zero when it cannot):
  double angle = 0;             ///< measured box angle (rad)
  double angleEquilibrium = 0;  ///< the statics' angle at q plus the angle's offset (rad)
  Eigen::Matrix<double, 1, 6> angleJacobian = Eigen::Matrix<double, 1, 6>::Zero();  ///< d angle/dq
  bool valid = false;  ///< the statics is smooth here (a Jacobian exists)
};

/// An affine map of the plan u (6N): value = offset + slope u.
struct MpcAffine {
  Eigen::VectorXd offset;
  Eigen::MatrixXd slope;
  Eigen::VectorXd at(const Eigen::VectorXd& u) const { return offset + slope * u; }
};

/// The predicted states at the end of each planned update k = 1..N (index k - 1).
struct MpcPrediction {
  std::vector<MpcAffine> commanded;  ///< joint targets (6)
  std::vector<MpcAffine> joints;     ///< joints (6)
  std::vector<MpcAffine> box;        ///< box centre (2)
  std::vector<MpcAffine> velocity;   ///< box velocity (2)
  std::vector<MpcAffine> angle;      ///< box angle (1): the equilibrium's at the joints
};

/// The horizon's prediction from the targets commanded now (`commanded`, reached by the servo
/// ramps at the start of the first update).
MpcPrediction predictHorizon(const HandModel& model, const HandMpcParams& params,
                             const MpcLinearisation& lin, const HandJoints& commanded);

/// The membranes' tensions (N) with fingertips at q and the box at `box` (turned by `angle`), and
/// their derivatives in q and in the box centre.
Eigen::Vector2d membraneTensions(const HandController& hand, const HandJoints& q, const Vec2& box,
                                 double angle = 0, Eigen::Matrix<double, 2, 6>* dq = nullptr,
                                 Eigen::Matrix2d* dbox = nullptr);

/// What the last update planned and what it cost.
struct MpcStatus {
  std::vector<Vec2> plannedBox;  ///< predicted box centre after each planned update (m)
  double solveMicros = 0;        ///< wall time of the whole update (us)
  int iterations = 0;            ///< active-set iterations
  double slack = 0;              ///< how far the constraints had to be relaxed (0: met)
  bool planned = false;          ///< false: the statics had no Jacobian, the hand held
};

class HandMpc {
 public:
  explicit HandMpc(HandModel model, HandMpcParams params = {});

  const HandMpcParams& params() const { return params_; }
  /// Forgets the servo model, the offset and the last plan (after a re-grasp).
  void reset();

  /// The model at the measured joints q, box centre and velocity, with the targets commanded now
  /// (advances the servo model by one period: call once per update, as update() does); `angle`
  /// the box's (rad; ignored when it cannot turn).
  MpcLinearisation linearise(const HandJoints& q, const Vec2& box, const Vec2& velocity,
                             const HandJoints& commanded, double angle = 0);

  /// One update: the joint-target increment to apply now (rad, m). `box` and `target` are
  /// (x, y, theta); the angles count only for a box that may turn.
  HandJoints update(const HandJoints& q, const BoxPose& box, const Vec2& velocity,
                    const BoxPose& target, const HandJoints& commanded);

  const MpcStatus& status() const { return status_; }

 private:
  HandMpcParams params_;
  HandController hand_;  ///< the statics model and its face-on conditions
  bool started_ = false;
  HandJoints servo_ = HandJoints::Zero(), previousCommanded_ = HandJoints::Zero();
  HandJoints expectedCommanded_ = HandJoints::Zero();
  Vec2 offset_ = Vec2::Zero();
  double angleOffset_ = 0;  ///< rad: the measured angle less the statics' (a box that turns)
  Eigen::VectorXd plan_;    ///< the last plan (6N), for the warm start
  MpcStatus status_;
};

/// Median wall time of one HandMpc::update at the pinch pose (us), over `repeats` calls.
double measureMpcUpdateMicros(int repeats = 200, int horizon = 6);

}  // namespace cablelab
