#include "engine/hand/hand_controller.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/core/small_qp.h"
#include "engine/statics/box_reduction.h"
#include "engine/statics/statics_sensitivity.h"

namespace cablelab {

namespace {
/// Ramp-following lag of the critically damped inner servos (s): 2 / omega.
double servoLag(const HandModel& m) {
  return 2 / std::sqrt(m.servoKp);
}
constexpr double kMaxSpeed = 2.0;          // m/s: a bound on the speed limit itself
constexpr double kFeedbackHeadroom = 2.0;  // the update may move the box this many reference steps
constexpr double kLimitMargin = 1e-9;      // rad or m: a joint this close to a limit is at it
constexpr int kLimitPasses = 3;            // re-solves of J+ after taking joints out
constexpr double kGapWeight = 100;         // the reference's direction holds the paddles' gap far
                                           // more firmly than it follows the target
}  // namespace

HandController::HandController(HandModel model, HandControllerParams params)
    : model_(std::move(model)), params_(params) {}

void HandController::reset() {
  integral_.setZero();
  previousError_.setZero();
  referenceVelocity_.setZero();
  started_ = hasSteering_ = false;
  status_ = {};
  angleVelocity_ = angleIntegral_ = 0;
  steeringAngle_.setZero();
  offset_.setZero(), startOffset_.setZero();
  angleOffset_ = 0;
}

std::vector<BoxCable> HandController::boxCables(const HandJoints& q) const {
  const FingertipPoints tips = fingertipPoints(model_, q);
  const double h = model_.boxHalfSize;
  std::vector<BoxCable> cables(2);
  for (int f = 0; f < 2; ++f) {
    BoxCable& c = cables[f];
    c.a = tips.segment<2>(4 * f);
    c.b = tips.segment<2>(4 * f + 2);
    c.k = model_.stiffness;
    // Tension k (length - rest + preload): the preload shortens the effective rest length.
    c.L = model_.restLength() - model_.preload;
    // The top membrane wraps the top face's two corners, the bottom one the bottom face's.
    const double face = HandModel::side(f) * h;
    c.cornerA = Vec2(-h, face);
    c.cornerB = Vec2(h, face);
  }
  return cables;
}

StaticsProblem HandController::staticsProblem(const HandJoints& q, const Vec2& guess) const {
  return reduceBoxToPoint(boxCables(q), guess);
}

BoxPrediction HandController::predict(const HandJoints& q, const Vec2& guess,
                                      double guessAngle) const {
  BoxPrediction out;
  if (model_.turn) {
    // The box in (x, y, theta): Newton on the membranes' energy (box_pose.h, docs/hand.md).
    const std::vector<BoxCable> cables = boxCables(q);
    const BoxPoseResult eq =
        solveBoxPose(cables, BoxPose(guess.x(), guess.y(), guessAngle), model_.boxHalfSize);
    out.box = eq.pose.head<2>();
    out.angle = eq.pose[2];
    if (!eq.converged) return out;
    Eigen::Vector3d gradient;
    Eigen::Matrix3d H;
    boxPoseEnergy(cables, eq.pose, &gradient, &H);
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(H);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.vectorD().minCoeff() <= 0)
      return out;  // no isolated equilibrium: no Jacobian
    const Eigen::Matrix<double, 3, 6> J =
        boxPoseSensitivity(cables, eq.pose) * fingertipJacobian(model_, q);
    out.jacobian = J.topRows<2>();
    out.angleJacobian = J.row(2);
    // The centre's stiffness with the angle settling freely (Schur complement).
    out.stiffness =
        H.topLeftCorner<2, 2>() - H.topRightCorner<2, 1>() * H.bottomLeftCorner<1, 2>() / H(2, 2);
    out.smooth = true;
    out.margin = faceOn(q, out).value.minCoeff();
    out.valid = out.margin > 0;
    return out;
  }
  const StaticsProblem problem = staticsProblem(q, guess);
  StaticsResult eq;
  solveStatics(problem, eq);
  out.box = eq.p;
  if (!eq.converged) return out;
  const StaticsSensitivity s = staticsSensitivity(problem, eq.p);
  if (s.kind != StaticsSensitivity::Kind::Smooth) return out;
  // The shift of figure 4-2 is a constant offset, so d p / d(shifted) = d p / d(fingertips).
  out.jacobian = s.dp * fingertipJacobian(model_, q);
  out.stiffness = staticsDerivatives(problem, eq.p).hessian;
  out.smooth = true;
  out.margin = faceOnMargin(model_, fingertipPoints(model_, q), eq.p);
  out.valid = out.margin > 0;
  return out;
}

double HandController::ellipseNorm(const Vec2& lag) const {
  const double along = params_.lagShare * (model_.paddleHalfWidth - model_.boxHalfSize);
  const double across =
      params_.lagShare * (model_.boxHalfSize - model_.baseY + model_.paddleOffset);
  return std::hypot(lag.x() / along, lag.y() / across);
}

double HandController::speedLimit(const Eigen::Matrix2d& K, const Vec2& d) const {
  const double c = model_.boxMass * model_.boxDamping;  // N s/m: the table's drag
  if (K.determinant() <= 1e-12 * K.squaredNorm() || d.norm() == 0) return 0;
  const Vec2 u = d.normalized();
  const Vec2 lag = c * K.inverse() * u + servoLag(model_) * u;  // m per (m/s)
  return std::min(kMaxSpeed, 1 / ellipseNorm(lag));
}

double HandController::accelerationLimit(const Eigen::Matrix2d& K, const Vec2& d) const {
  // Change speed no faster than the box's own velocity decays under the table's drag (time
  // 2 m / c), twice over: the membranes' sideways mode (damping ratio about 0.5) is not rung.
  const double decay = 2 * model_.boxMass / (model_.boxMass * model_.boxDamping);
  return speedLimit(K, d) / (2 * decay);
}

void HandController::advanceReference(const Vec2& box, const Vec2& target) {
  const double T = params_.period;
  const Vec2 toGo = target - reference_;
  const double distance = toGo.norm();
  Vec2 desired = Vec2::Zero();
  if (distance > 0) {
    const Vec2 d = toGo / distance;
    const double a = accelerationLimit(stiffness_, d);
    // Cruise at the membranes' speed, brake in time to stop at the target, never overshoot.
    double v = std::min({speedLimit(stiffness_, d), std::sqrt(2 * a * distance), distance / T});
    // Slow down as the box falls behind its model, or the commanded equilibrium behind the
    // reference (the joints at their limits cannot deliver it).
    const Vec2 equilibrium =
        commandedPrediction_.smooth ? Vec2(commandedPrediction_.box + offset_) : reference_;
    const double behind = std::max((modelBox_ + offset_ - startOffset_ - box).norm(),
                                   (equilibrium - reference_).norm());
    const double wait =
        std::clamp((params_.leadLimit - behind) / (0.5 * params_.leadLimit), 0.0, 1.0);
    v *= wait;
    // Along what the joints can deliver: at a joint limit or where the membranes would stop
    // wrapping the box face-on the reference turns along that boundary at the membranes' speed
    // while it still gets closer, braking as the share of the target's direction that the
    // boundary still allows shrinks (for a straight boundary that share times the distance is
    // the way left to the nearest point): a target outside the reachable set leads to the set's
    // nearest point.
    if (commandedPrediction_.smooth && v > 0) {
      const FeasibleMotion m = feasibleDirection(d, v, a);
      const double share = m.motion.norm();
      if (!m.bounded) {
        desired = v * d;
      } else if (share > 0) {
        const Vec2 u = m.motion / share;
        const double au = accelerationLimit(stiffness_, u);
        desired = u * wait *
                  std::min({speedLimit(stiffness_, u), std::sqrt(2 * au * share * distance),
                            share * distance / T});
      }
    }
  }
  Vec2 dv = desired - referenceVelocity_;
  const double aMax = accelerationLimit(stiffness_, dv);
  if (dv.norm() > aMax * T) dv *= aMax * T / dv.norm();
  referenceVelocity_ += dv;
  // Never step past the target (the last step of a stop lands on it).
  if ((referenceVelocity_ * T).norm() >= distance)
    reference_ = target, referenceVelocity_ = toGo / T;
  else
    reference_ += referenceVelocity_ * T;
  if (reference_ == target && dv.norm() == 0) referenceVelocity_.setZero();
  status_.speedLimit = distance > 0 ? speedLimit(stiffness_, toGo) : 0;
}

Eigen::Matrix<double, 12, 6> HandController::faceOnJacobian(const HandJoints& q,
                                                            const BoxPrediction& p) const {
  // Each condition is linear in the fingertips and the box; both move with the joints, the box
  // through the statics (p.jacobian, p.angleJacobian).
  const FaceOnTerms terms = faceOn(q, p);
  Eigen::Matrix<double, 12, 6> J =
      terms.dTips * fingertipJacobian(model_, q) + terms.dBox * p.jacobian;
  if (model_.turn) J += terms.dAngle * p.angleJacobian;
  return J;
}

FaceOnTerms HandController::faceOn(const HandJoints& q, const BoxPrediction& p) const {
  const FingertipPoints tips = fingertipPoints(model_, q);
  return model_.turn ? faceOnTerms(model_, tips, p.box, p.angle) : faceOnTerms(model_, tips, p.box);
}

Eigen::Matrix<double, 1, 6> HandController::angleRow() const {
  return params_.angleArm * steeringAngle_;
}

Eigen::Matrix<double, 6, 6> HandController::stepMetric(const BoxJacobian& J,
                                                       const Eigen::Matrix<double, 2, 6>& G,
                                                       double gapWeight) const {
  // |J dq|^2 + w |G dq|^2 + lambda^2 dq^T W^-1 dq: the damped, weighted least squares of the
  // stacked task (the distal joints cost distalWeight times more).
  HandJoints cost = HandJoints::Ones();
  cost[kDistal] = cost[3 + kDistal] = params_.distalWeight;
  Eigen::Matrix<double, 6, 6> M =
      J.transpose() * J + gapWeight * G.transpose() * G +
      params_.lambda * params_.lambda * Eigen::Matrix<double, 6, 6>(cost.asDiagonal());
  // A box that turns: its angle is held (or followed) as firmly as the gap.
  if (model_.turn) M += gapWeight * angleRow().transpose() * angleRow();
  return M;
}

void HandController::stepConstraints(double scale, Eigen::Matrix<double, 24, 6>& C,
                                     Eigen::Matrix<double, 24, 1>& b) const {
  // Rows 0-11 the face-on conditions (the caller sets their bounds), rows 12-23 the joint limits
  // of the commanded joints for a step scale * dq.
  C.topRows<12>() = faceOnJacobian(steeringJoints_, commandedPrediction_);
  for (int j = 0; j < 6; ++j) {
    C.row(12 + 2 * j).setZero(), C.row(13 + 2 * j).setZero();
    C(12 + 2 * j, j) = 1,
                  b[12 + 2 * j] = std::min(0.0, model_.lower[j] - steeringJoints_[j]) / scale;
    C(13 + 2 * j, j) = -1,
                  b[13 + 2 * j] = std::min(0.0, steeringJoints_[j] - model_.upper[j]) / scale;
  }
}

HandController::FeasibleMotion HandController::feasibleDirection(const Vec2& d, double v,
                                                                 double a) const {
  // Joint motion dq per metre of reference travel: the least-squares step towards J dq = d with
  // the paddles' gap held (G dq = 0, weighted far above the direction), bounded by
  //   joint limits  v T dq_j within [lower_j - c_j, upper_j - c_j] (c the commanded joints),
  //   face-on       v (g_i . dq) >= -sqrt(2 a room_i): each condition's slack room_i beyond
  //                 wrapMargin shrinks no faster than the reference can brake to a stop on it.
  const BoxJacobian& J = commandedPrediction_.jacobian;
  Vec2 gap;
  const Eigen::Matrix<double, 2, 6> G = gapJacobian(commanded_, gap);
  Eigen::Matrix<double, 24, 6> C;
  Eigen::Matrix<double, 24, 1> b;
  stepConstraints(v * params_.period, C, b);
  const FaceOnTerms terms = faceOn(steeringJoints_, commandedPrediction_);
  for (int i = 0; i < 12; ++i)
    b[i] = -std::sqrt(2 * a * std::max(0.0, terms.value[i] - params_.wrapMargin)) / v;
  const SmallQpResult r = solveSmallQp(stepMetric(J, G, kGapWeight), -J.transpose() * d, C, b,
                                       Eigen::VectorXd::Zero(6));
  return {J * r.x, !r.active.empty()};
}

HandJoints HandController::boundedStep(const HandJoints& dq, const BoxJacobian& J,
                                       const Eigen::Matrix<double, 2, 6>& G,
                                       const HandJoints& winv) const {
  // The step nearest dq in the task's metric that keeps the commanded joints within their limits
  // and every face-on condition at least wrapMargin (restoring one that has fallen below).
  if (!commandedPrediction_.smooth) return dq;
  Eigen::Matrix<double, 24, 6> C;
  Eigen::Matrix<double, 24, 1> b;
  stepConstraints(1, C, b);
  const FaceOnTerms terms = faceOn(steeringJoints_, commandedPrediction_);
  for (int i = 0; i < 12; ++i) b[i] = params_.wrapMargin - terms.value[i];
  if ((C * dq - b).minCoeff() >= 0) return dq;
  Eigen::Matrix<double, 6, 6> M = stepMetric(J, G, 1);
  for (int j = 0; j < 6; ++j)
    if (winv[j] == 0) M(j, j) += 1e6;  // joints taken out at a limit stay out
  const SmallQpResult r = solveSmallQp(M, -M * dq, C, b, Eigen::VectorXd::Zero(6));
  return r.x;
}

void HandController::advanceServos(const HandJoints& commanded) {
  // The servo targets ramped from the previous command to this one over the last period.
  constexpr int kSubsteps = 8;
  const double decay = 1 - std::exp(-params_.period / kSubsteps / servoLag(model_));
  for (int i = 1; i <= kSubsteps; ++i)
    servoJoints_ += (previousCommanded_ +
                     (commanded - previousCommanded_) * (double(i) / kSubsteps) - servoJoints_) *
                    decay;
  previousCommanded_ = commanded;
}

void HandController::advanceModel(const Vec2& from) {
  // One period: the servo targets ramp linearly from the previous reference to the new one (the
  // grasp sequence spreads every update over the period), the servos follow with lag tau_s, the
  // box with its mass, the table's drag and the membranes' stiffness. Implicit Euler.
  constexpr int kSubsteps = 8;
  const double h = params_.period / kSubsteps, tau = servoLag(model_);
  const double c = model_.boxMass * model_.boxDamping;
  for (int i = 1; i <= kSubsteps; ++i) {
    const Vec2 r = from + (reference_ - from) * (double(i) / kSubsteps);
    servoReference_ += (r - servoReference_) * (1 - std::exp(-h / tau));
    // Implicit in the velocity: stable however stiff the pinch (K grows near a fingertip).
    const Eigen::Matrix2d A =
        (model_.boxMass + h * c) * Eigen::Matrix2d::Identity() + h * h * stiffness_;
    modelVelocity_ = A.ldlt().solve(model_.boxMass * modelVelocity_ +
                                    h * stiffness_ * (servoReference_ - modelBox_));
    modelBox_ += h * modelVelocity_;
  }
}

Eigen::Matrix<double, 2, 6> HandController::gapJacobian(const HandJoints& commanded,
                                                        Vec2& gap) const {
  // gap = D_top - D_bottom - (0, 2 baseY), D a finger's distal joint (the paddle's origin).
  Eigen::Matrix<double, 2, 6> G = Eigen::Matrix<double, 2, 6>::Zero();
  const FingerPose top = fingerPose(model_, commanded, 0),
                   bottom = fingerPose(model_, commanded, 1);
  gap = top.paddle - bottom.paddle -
        (model_.turn ? rotate(Vec2(0, 2 * model_.baseY), angleReference_)
                     : Vec2(0, 2 * model_.baseY));
  for (int f = 0; f < 2; ++f) {
    const FingerPose& pose = f == 0 ? top : bottom;
    const double sign = f == 0 ? 1.0 : -1.0;
    G.col(3 * f + kProximal) = sign * perp(pose.paddle - pose.link);
    G.col(3 * f + kSlide) = sign * Vec2(std::cos(pose.linkAngle), std::sin(pose.linkAngle));
  }
  return G;
}

HandJoints HandController::nullSpaceTask(const HandJoints& commanded,
                                         const HandJoints& winv) const {
  // h(q) = sum tilt^2 (paddles face-on), on the commanded targets, not the measured joints: the
  // servos lag under load and a task on the measured joints would wind up.
  HandJoints gradient = HandJoints::Zero();
  for (int f = 0; f < 2; ++f) {
    double tilt = commanded[3 * f + kProximal] + commanded[3 * f + kDistal];
    if (model_.turn) tilt -= angleReference_;  // face-on to the turned box
    gradient[3 * f + kProximal] = tilt;
    gradient[3 * f + kDistal] = tilt;
  }
  return -params_.faceOnGain * winv.asDiagonal() * gradient;
}

void HandController::advanceAngleReference(double target) {
  // As the centre's reference: cruise at angleSpeed, brake in time, never overshoot.
  const double T = params_.period, a = params_.angleAcceleration;
  const double toGo = target - angleReference_;
  const double desired = std::copysign(
      std::min({params_.angleSpeed, std::sqrt(2 * a * std::abs(toGo)), std::abs(toGo) / T}), toGo);
  angleVelocity_ += std::clamp(desired - angleVelocity_, -a * T, a * T);
  if (std::abs(angleVelocity_ * T) >= std::abs(toGo))
    angleReference_ = target, angleVelocity_ = 0;
  else
    angleReference_ += angleVelocity_ * T;
}

template <int Tasks>
HandJoints HandController::stackedStep(const Eigen::Matrix<double, Tasks, 6>& A,
                                       const Eigen::Matrix<double, Tasks, 1>& task,
                                       const HandJoints& commanded, HandJoints& winv,
                                       HandJoints& primary) const {
  // Weighted damped pseudo-inverse of the stacked task; joints the step would push through a
  // limit drop out (winv zeroed) and the others take over.
  HandJoints dq = HandJoints::Zero();
  for (int pass = 0; pass < kLimitPasses; ++pass) {
    const Eigen::Matrix<double, 6, Tasks> AWt = winv.asDiagonal() * A.transpose();
    const Eigen::Matrix<double, Tasks, Tasks> AWAt =
        A * AWt + params_.lambda * params_.lambda * Eigen::Matrix<double, Tasks, Tasks>::Identity();
    const Eigen::Matrix<double, 6, Tasks> pinv = AWt * AWAt.inverse();
    const Eigen::Matrix<double, 6, 6> nullspace =
        Eigen::Matrix<double, 6, 6>::Identity() - pinv * A;
    primary = pinv * task;
    dq = primary + nullspace * nullSpaceTask(commanded, winv);
    bool blocked = false;
    for (int j = 0; j < 6; ++j) {
      const bool atUpper = commanded[j] >= model_.upper[j] - kLimitMargin && dq[j] > 0;
      const bool atLower = commanded[j] <= model_.lower[j] + kLimitMargin && dq[j] < 0;
      if (winv[j] > 0 && (atUpper || atLower)) winv[j] = 0, blocked = true;
    }
    if (!blocked) break;
  }
  return dq;
}

HandJoints HandController::update(const HandJoints& q, const Vec2& box, const Vec2& target,
                                  const HandJoints& commanded) {
  return update(q, BoxPose(box.x(), box.y(), 0), BoxPose(target.x(), target.y(), 0), commanded);
}

HandJoints HandController::update(const HandJoints& q, const BoxPose& boxPose,
                                  const BoxPose& targetPose, const HandJoints& commanded) {
  const Vec2 box = boxPose.head<2>(), target = targetPose.head<2>();
  // A box that cannot turn has angle 0 and so has its target: every angle term below vanishes.
  const bool turn = model_.turn;
  const double angle = turn ? boxPose[2] : 0, targetAngle = turn ? targetPose[2] : 0;
  last_ = predict(q, box, angle);
  // The loop steers the equilibrium the fingers settle to: the commanded joints plus the servos'
  // static droop under the membranes' load (the measured joints minus the commanded ones as the
  // servos' ramp lag would have them). The servos' and the box's lags behind it are physics the
  // reference model expects, not errors.
  if (!started_) servoJoints_ = previousCommanded_ = commanded;
  advanceServos(commanded);
  commanded_ = commanded;
  steeringJoints_ = commanded + (q - servoJoints_);
  commandedPrediction_ =
      predict(steeringJoints_, started_ ? reference_ : box, started_ ? angleReference_ : angle);
  const BoxPrediction& p = commandedPrediction_;
  // The reduction's Jacobian steers wherever the statics is smooth, also with a paddle tilted
  // beyond face-on (the equilibrium still follows the box there to a centimetre or so; a stale
  // Jacobian does not). Where it is not smooth: the last one; the null-space task brings the
  // grasp back to the pinch geometry.
  if (p.smooth)
    steering_ = p.jacobian, stiffness_ = p.stiffness, steeringAngle_ = p.angleJacobian,
    hasSteering_ = true;
  if (!hasSteering_) return HandJoints::Zero();
  const double T = params_.period;
  const bool first = !started_;
  // Friction: where the box rests against the frictionless statics at the measured joints (zero
  // without friction, the thesis's model). The box's rest pose then depends on its way there;
  // unseen, the offset held the box behind the reference model by leadLimit, so the reference
  // waited and the box crept (docs/control.md#membrane-friction).
  if (model_.friction > 0 && last_.smooth) {
    const Vec2 seen = box - last_.box;
    const double seenAngle = angle - last_.angle;
    if (first) {
      offset_ = startOffset_ = seen, angleOffset_ = seenAngle;
    } else if ((box - previousBox_).norm() < params_.restSpeed * T) {
      offset_ += params_.offsetGain * (seen - offset_);
      angleOffset_ += params_.offsetGain * (seenAngle - angleOffset_);
    }
  }
  previousBox_ = box;
  if (first) {
    reference_ = servoReference_ = modelBox_ = box;
    referenceVelocity_.setZero(), modelVelocity_.setZero();
    angleReference_ = angle, angleVelocity_ = 0;
    started_ = true;
  }
  const Vec2 previousReference = reference_;
  const double previousAngle = angleReference_;
  advanceReference(box, target);
  if (turn) advanceAngleReference(targetAngle);
  advanceModel(previousReference);
  // Feedback in three parts (docs/controller.md). k_p acts on the commanded equilibrium's
  // departure from the reference: it corrects the linearisation and never feeds the box's own lag
  // back (fed back through the rate law, that lag integrates into an overshoot). k_d acts on the
  // box's departure from the reference model: it damps the box's sway on the membranes. The
  // integral collects the box's offset from the target once the reference rests there: the
  // statics model's own error, which PD leaves.
  // Once the reference rests on the target the lag has gone and k_p acts on the box itself.
  const bool resting = reference_ == target && angleReference_ == targetAngle;
  const Vec2 modelError = resting    ? Vec2(box - target)
                          : p.smooth ? Vec2(p.box + offset_ - reference_)
                                     : Vec2::Zero();
  const Vec2 error = box - modelBox_;
  const Vec2 change = first ? Vec2::Zero() : Vec2(error - previousError_);
  previousError_ = error;

  // The box displacement asked of this update: feedforward plus feedback, rate-limited.
  Vec2 want = (reference_ - previousReference) - params_.kp * modelError - params_.kd * change -
              params_.ki * T * integral_;
  const double cap = kFeedbackHeadroom * T * speedLimit(stiffness_, want);
  status_ = {reference_, modelBox_, error, integral_, status_.speedLimit, false, 0, p.margin};
  if (want.norm() > cap) want *= cap / want.norm(), status_.rateLimited = true;
  // The angle the same way (its equilibrium against the reference while that moves, the box
  // against the target once it rests), without a sway model: the table's drag damps the turning.
  double wantAngle = 0;
  if (turn) {
    const double angleError = resting    ? angle - targetAngle
                              : p.smooth ? p.angle + angleOffset_ - angleReference_
                                         : 0.0;
    wantAngle = (angleReference_ - previousAngle) - params_.kp * angleError -
                params_.ki * T * angleIntegral_;
    const double angleCap = kFeedbackHeadroom * T * params_.angleSpeed;
    if (std::abs(wantAngle) > angleCap)
      wantAngle = std::copysign(angleCap, wantAngle), status_.rateLimited = true;
  }

  // Weighted damped pseudo-inverse of the box task (and its angle) stacked with the paddles' gap:
  // the gap is held at the pinch's (0, 2 baseY) as a task of its own, not in the null space, so
  // that when joints saturate the fingers cannot spread apart and let the box out.
  const BoxJacobian& J = steering_;
  Vec2 gap;
  const Eigen::Matrix<double, 2, 6> G = gapJacobian(commanded, gap);
  HandJoints winv = HandJoints::Ones();
  winv[kDistal] = winv[3 + kDistal] = 1.0 / params_.distalWeight;
  HandJoints dq, primary;
  if (turn) {
    Eigen::Matrix<double, 5, 6> A;
    A << J, angleRow(), G;
    Eigen::Matrix<double, 5, 1> task;
    task << want, params_.angleArm * wantAngle, -params_.faceOnGain * gap;
    dq = stackedStep<5>(A, task, commanded, winv, primary);
  } else {
    Eigen::Matrix<double, 4, 6> A;
    A << J, G;
    Eigen::Vector4d task;
    task << want, -params_.faceOnGain * gap;
    dq = stackedStep<4>(A, task, commanded, winv, primary);
  }
  status_.jointsAtLimit = static_cast<int>((winv.array() == 0).count());
  // Bounded by the joint limits and the face-on conditions. While the reference moves, what the
  // bound takes off the box's motion comes off the reference too (back-calculation): it never
  // runs ahead of what the joints can deliver, so it keeps sliding along the boundary instead of
  // waiting outside it. Once it rests on the target it stays there (the integral's anti-windup
  // below handles a bound then).
  const HandJoints bounded = boundedStep(dq, J, G, winv);
  if (bounded != dq && !resting) {
    reference_ += J * (bounded - dq);
    if (turn) angleReference_ += steeringAngle_ * (bounded - dq);
    status_.reference = reference_;
  }
  primary += bounded - dq, dq = bounded;
  // Anti-windup: collect the error only once the reference rests on the target and the update
  // is not saturated (the requested motion is what the joints deliver).
  const HandJoints clipped = model_.clamp(commanded + dq) - (commanded + dq);
  const Vec2 delivered = J * (primary + clipped);  // the box part of the stacked task
  bool saturated = status_.rateLimited || (delivered - want).norm() > 0.2 * want.norm() + 1e-9;
  if (turn) {  // the centre and the angle (in metres at the corners) as one task
    const double arm = params_.angleArm, turned = steeringAngle_ * (primary + clipped);
    const Eigen::Vector3d asked(want.x(), want.y(), arm * wantAngle),
        got(delivered.x(), delivered.y(), arm * turned);
    saturated = status_.rateLimited || (got - asked).norm() > 0.2 * asked.norm() + 1e-9;
  }
  if (!saturated && resting) {
    integral_ += (box - target) * T;
    if (turn) angleIntegral_ += (angle - targetAngle) * T;
  }
  status_.integral = integral_;
  status_.angleReference = angleReference_;
  status_.offset = offset_;
  return dq;
}

double measureControllerUpdateMicros(int repeats) {
  using Clock = std::chrono::steady_clock;
  HandController controller{HandModel{}};
  const HandJoints q = HandJoints::Zero();
  const Vec2 box = controller.predict(q, Vec2::Zero()).box;
  std::vector<double> micros;
  micros.reserve(repeats / 100 + 1);
  double sink = 0;
  // Time batches of 100 updates (a single update is near the clock's resolution).
  for (int r = 0; r < std::max(1, repeats / 100); ++r) {
    const auto t0 = Clock::now();
    for (int i = 0; i < 100; ++i) sink += controller.update(q, box, Vec2(0.01 * (i % 3), 0), q)[0];
    micros.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / 100);
  }
  std::nth_element(micros.begin(), micros.begin() + micros.size() / 2, micros.end());
  volatile double keep = sink;  // the updates must not be optimised away
  (void)keep;
  return micros[micros.size() / 2];
}

}  // namespace cablelab
