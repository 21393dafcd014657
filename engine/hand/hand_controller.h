// The statics-based Jacobian controller of thesis section 4.3 (outer loop).
//
//   db/dq_u = db/dp_ij * dp_ij/dq_u                 (2 x 6: statics sensitivity x fingertip FK)
//   dq_u    = A+ (dr - k_p e - k_d de - k_i T sum e_box, gap task)  per outer update (period T),
//   A+      = W^-1 A^T (A W^-1 A^T + l^2 I)^-1,  A = [db/dq_u; d gap/dq_u]   (4 x 6)
// Equation (4.4) of the thesis is a joint *rate* from a 2-vector, q_dot = -J+ (k_p' e + k_d b_dot)
// (docs/control.md#controller); integrated over one period it is a law of this form, k_p the share
// of the error removed per update (dimensionless, k_p' = k_p / T), k_d dimensionless on the
// error's change over one period, k_i per update per second (1/s).
//
// What keeps the grasp (beyond the thesis):
//  * The box follows a reference r, not the target. r moves towards the target no faster than
//    the membranes can carry the box: at velocity v the box lags by (c K^-1 + tau_s) v, with c
//    the table's drag (box mass x damping), K the box's stiffness (the statics Hessian) and tau_s
//    the servos' ramp lag; that lag must stay within `lagShare` of the membranes' room (along
//    and across the paddles). It speeds up and brakes over twice the box's velocity decay time,
//    so a target jump becomes a smooth ramp. r waits while the box falls behind the reference
//    model or the commanded equilibrium behind r.
//  * r moves along what the joints can deliver (docs/control.md#controller): the box motion of a
//    bounded least-squares joint step towards the target, within the joint limits and keeping
//    every face-on condition `wrapMargin` from failing (braking in time). At the boundary of the
//    reachable set it turns along the boundary while that still gets closer, so a target outside
//    the set leads the box, still held, to the set's nearest point. The update's step is bounded
//    the same way, and what the bound removes comes off r too (back-calculation).
//  * A reference model (servo lag, then the box's mass, drag and K) says where the box should be;
//    its own lag is expected, not fed back. k_p acts on the equilibrium of the commanded joints
//    (plus the servos' static droop) against r while r moves, on the box against the target once
//    r rests there; k_d on the box's departure from the reference model.
//  * The feedforward dr moves the statics equilibrium with r.
//  * Joints at a limit that the update would push further are taken out of A+ (their weight
//    zeroed) so the others take over; the bounded step then keeps the joints within their limits.
//  * The integral collects the box's error only once r rests on the target and the update is
//    not saturated (by the rate limit or by joint limits): no wind-up during the ramp or against
//    a limit, and an offset of any size within the reachable set is removed.
//  * The paddles' gap is held at the pinch's as a task stacked with the box's (so saturated
//    joints cannot spread the fingers), and the null space turns each paddle back towards face-on
//    (theta_p + theta_d -> 0): both membranes keep wrapping the box face-on, the configuration
//    the box-to-point reduction (box_reduction.h) assumes.
#pragma once

#include <Eigen/Core>

#include "engine/hand/hand_kinematics.h"
#include "engine/hand/hand_model.h"
#include "engine/statics/box_pose.h"
#include "engine/statics/statics.h"

namespace cablelab {

struct HandControllerParams {
  double period = 0.053;  ///< outer-loop period (s)
  double kp = 0.1;        ///< per update, dimensionless (thesis k_p)
  double kd = 0.58;       ///< dimensionless, on the error's change over one period (thesis k_d)
  double ki = 0.0;        ///< per update per second (1/s); > 0 for PID
  double lambda = 0.05;   ///< pseudo-inverse damping (m per rad or m per m)
  /// Share of the membranes' room the box may lag by while it moves: along the paddles the box
  /// has paddleHalfWidth - boxHalfSize before a corner reaches the paddle's end, across them the
  /// indentation of the pinch (boxHalfSize - baseY + paddleOffset).
  double lagShare = 0.2;
  double wrapMargin = 0.005;  ///< every face-on condition keeps this much slack (m): the
                              ///< reference brakes in time and slides along it
  double leadLimit = 0.03;    ///< the reference slows once the box is this far off the
                              ///< reference model (m), or the commanded equilibrium off it
  double distalWeight = 4.0;  ///< joint-space weight of the distal joints in the pseudo-inverse
                              ///< (> 1: prefer moving the fingers to tilting the paddles)
  double faceOnGain = 0.3;    ///< per update: null-space pull back to face-on paddles and the
                              ///< pinch gap
  /// A box that turns (HandModel::turn): the angle reference's top speed (rad/s) and
  /// acceleration (rad/s^2); the angle's share of the stacked task counts a radian as this many
  /// metres (the box's half side: the corners move that far per radian).
  double angleSpeed = 0.25;
  double angleAcceleration = 0.25;
  double angleArm = 0.25;
  /// Membranes with friction (HandModel::friction > 0): the box rests off the frictionless
  /// statics' equilibrium by an offset that depends on the way it came. Below this speed (m/s)
  /// the offset is measured, a share `offsetGain` per update, and the statics' equilibria are
  /// shifted by it.
  double restSpeed = 0.02;
  double offsetGain = 0.3;
};

/// The integral gain `--pid` uses (1/s per update).
inline constexpr double kHandPidKi = 1.0;

/// db/dq_u (m/rad, m/m), 2 x 6.
using BoxJacobian = Eigen::Matrix<double, 2, 6>;

/// The statics model's prediction at joint values q.
struct BoxPrediction {
  Vec2 box = Vec2::Zero();  ///< equilibrium box centre (m)
  BoxJacobian jacobian = BoxJacobian::Zero();
  /// d2E/db2 at the equilibrium (N/m); for a box that turns, with the angle free (the Schur
  /// complement of the (x, y, theta) Hessian).
  Eigen::Matrix2d stiffness = Eigen::Matrix2d::Zero();
  double angle = 0;  ///< equilibrium box angle (rad); 0 for a box that cannot turn
  Eigen::Matrix<double, 1, 6> angleJacobian =
      Eigen::Matrix<double, 1, 6>::Zero();  ///< d angle/dq_u
  bool smooth = false;  ///< solver converged and the equilibrium is smooth (jacobian exists)
  bool valid = false;   ///< smooth and both membranes wrap the box face-on
  double margin = 0;    ///< faceOnMargin() at the equilibrium (m)
};

/// What the last update did (for diagnostics and tests).
struct ControllerStatus {
  Vec2 reference = Vec2::Zero();  ///< r (m)
  Vec2 expected = Vec2::Zero();   ///< where the box model, driven by r, has the box (m)
  Vec2 error = Vec2::Zero();      ///< b - expected (m)
  Vec2 integral = Vec2::Zero();   ///< sum e dt (m s)
  double speedLimit = 0;          ///< the reference's speed limit along its motion (m/s)
  bool rateLimited = false;       ///< the update was scaled down to the rate limit
  int jointsAtLimit = 0;          ///< joints taken out of J+ at their limits
  double margin = 0;              ///< faceOnMargin() of the commanded joints' equilibrium (m)
  double angleReference = 0;      ///< the box angle's reference (rad; 0 if it cannot turn)
  Vec2 offset = Vec2::Zero();     ///< friction: the box's offset from the statics (m)
};

class HandController {
 public:
  explicit HandController(HandModel model, HandControllerParams params = {});

  const HandModel& model() const { return model_; }
  const HandControllerParams& params() const { return params_; }
  /// New gains from the next update on (the reference, model and integral are kept).
  void setParams(const HandControllerParams& params) { params_ = params; }

  /// The statics problem of the box-to-point reduction at joints q (warm start `guess`): the two
  /// membranes as point cables, fingertips shifted by the box corners they wrap.
  StaticsProblem staticsProblem(const HandJoints& q, const Vec2& guess) const;

  /// The two membranes as cables over the box's wrapped faces (box_pose.h), fingertips at q.
  std::vector<BoxCable> boxCables(const HandJoints& q) const;

  /// Equilibrium box centre, db/dq_u and the box stiffness at joints q, warm-started at `guess`
  /// (and `guessAngle` when the box may turn: then the statics in (x, y, theta), box_pose.h).
  BoxPrediction predict(const HandJoints& q, const Vec2& guess, double guessAngle = 0) const;

  /// Clears the integral, the derivative memory and the reference (the next update starts the
  /// reference at the box).
  void reset();

  /// One outer-loop update from the measured joints q and box centre, the target and the joint
  /// targets currently commanded; returns the joint-target increment (rad, m). Call it once per
  /// period.
  HandJoints update(const HandJoints& q, const Vec2& box, const Vec2& target,
                    const HandJoints& commanded);
  /// The same for a box that may turn: box and target as (x, y, theta). For a box that cannot
  /// turn the angles are ignored (the update above).
  HandJoints update(const HandJoints& q, const BoxPose& box, const BoxPose& target,
                    const HandJoints& commanded);

  /// The face-on conditions at joints q with the box where p has it (turned by p.angle).
  FaceOnTerms faceOn(const HandJoints& q, const BoxPrediction& p) const;
  /// d(face-on conditions)/dq at joints q with the prediction p there (12 x 6, faceOnTerms()'s
  /// rows): the fingertips move with q, the box with p.jacobian (and p.angleJacobian).
  Eigen::Matrix<double, 12, 6> faceOnJacobian(const HandJoints& q, const BoxPrediction& p) const;

  /// The last update's prediction and status (for diagnostics).
  const BoxPrediction& lastPrediction() const { return last_; }
  const ControllerStatus& status() const { return status_; }

  /// Box speed (m/s) the membranes can follow along direction `d` with box stiffness K: the
  /// lag (c K^-1 + tau_s) v, with c the table's drag and tau_s the servos' ramp lag, kept
  /// within the lag ellipse (lagShare of the room along and across the paddles).
  double speedLimit(const Eigen::Matrix2d& stiffness, const Vec2& d) const;
  /// Acceleration (m/s^2) along `d`: the speed limit reached over twice the box's velocity decay
  /// time under the table's drag (2 m / c).
  double accelerationLimit(const Eigen::Matrix2d& stiffness, const Vec2& d) const;

 private:
  void advanceReference(const Vec2& box, const Vec2& target);
  void advanceAngleReference(double target);
  template <int Tasks>
  HandJoints stackedStep(const Eigen::Matrix<double, Tasks, 6>& A,
                         const Eigen::Matrix<double, Tasks, 1>& task, const HandJoints& commanded,
                         HandJoints& winv, HandJoints& primary) const;
  void advanceModel(const Vec2& from);
  void advanceServos(const HandJoints& commanded);
  double ellipseNorm(const Vec2& lag) const;
  struct FeasibleMotion {
    Vec2 motion;   ///< box motion per metre of reference travel along d (|.| <= about 1)
    bool bounded;  ///< a joint limit or a face-on condition shaped it
  };
  FeasibleMotion feasibleDirection(const Vec2& d, double v, double a) const;
  HandJoints boundedStep(const HandJoints& dq, const BoxJacobian& J,
                         const Eigen::Matrix<double, 2, 6>& G, const HandJoints& winv) const;
  Eigen::Matrix<double, 6, 6> stepMetric(const BoxJacobian& J, const Eigen::Matrix<double, 2, 6>& G,
                                         double gapWeight) const;
  /// The angle's row of the stacked task (angleArm x d angle/dq; zero if the box cannot turn).
  Eigen::Matrix<double, 1, 6> angleRow() const;
  void stepConstraints(double scale, Eigen::Matrix<double, 24, 6>& C,
                       Eigen::Matrix<double, 24, 1>& b) const;
  HandJoints nullSpaceTask(const HandJoints& commanded, const HandJoints& winv) const;
  /// d gap/dq and the gap itself, the paddles' distal joints' offset from the pinch's, the
  /// pinch turned by the angle reference when the box may turn.
  Eigen::Matrix<double, 2, 6> gapJacobian(const HandJoints& commanded, Vec2& gap) const;

  HandModel model_;
  HandControllerParams params_;
  Vec2 integral_ = Vec2::Zero();
  Vec2 previousError_ = Vec2::Zero();
  Vec2 reference_ = Vec2::Zero(), referenceVelocity_ = Vec2::Zero();
  // The reference model: the pinch's equilibrium follows r through the servos (first-order lag
  // tau_s), the box follows the equilibrium (mass, the table's drag, stiffness K).
  Vec2 servoReference_ = Vec2::Zero(), modelBox_ = Vec2::Zero(), modelVelocity_ = Vec2::Zero();
  bool started_ = false;
  BoxJacobian steering_ = BoxJacobian::Zero();  ///< the last valid prediction's Jacobian
  Eigen::Matrix2d stiffness_ = Eigen::Matrix2d::Zero();
  bool hasSteering_ = false;
  BoxPrediction last_, commandedPrediction_;
  HandJoints servoJoints_ = HandJoints::Zero(), previousCommanded_ = HandJoints::Zero();
  HandJoints commanded_ = HandJoints::Zero();       ///< the joint targets of this update
  HandJoints steeringJoints_ = HandJoints::Zero();  ///< commanded plus the servos' droop
  ControllerStatus status_;
  // A box that turns: the angle's reference, its rate, the integral and the last valid d angle/dq.
  double angleReference_ = 0, angleVelocity_ = 0, angleIntegral_ = 0;
  Eigen::Matrix<double, 1, 6> steeringAngle_ = Eigen::Matrix<double, 1, 6>::Zero();
  // Friction: the box's offset from the frictionless statics at the measured joints (and its
  // angle's), as measured at the first update and now; the box at the last update.
  Vec2 offset_ = Vec2::Zero(), startOffset_ = Vec2::Zero(), previousBox_ = Vec2::Zero();
  double angleOffset_ = 0;
};

/// Median wall time of one HandController::update at the pinch pose (us), over `repeats` calls.
double measureControllerUpdateMicros(int repeats = 20000);

}  // namespace cablelab
