#include "engine/hand/hand_mpc.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/core/small_qp.h"

namespace cablelab {

namespace {

constexpr int kMpcSubsteps = 8;  // per update: the servo ramp and the box's motion, implicit Euler

/// The servos' ramp lag (s), as the Jacobian controller's reference model has it: 2 / omega.
double mpcServoLag(const HandModel& m) {
  return 2 / std::sqrt(m.servoKp);
}

/// The state the prediction carries, each row an affine function of the plan: column 0 the
/// offset, columns 1.. the slope (6N).
struct AffineState {
  Eigen::MatrixXd joints, box, velocity;  // 6, 2, 2 rows
};

MpcAffine affine(const Eigen::MatrixXd& m) {
  return {m.col(0), m.rightCols(m.cols() - 1)};
}

/// d(paddles' gap)/d(fingertips): the top membrane's corners' midpoint less the bottom one's
/// (the pinch holds it at (0, 2 (baseY - paddleOffset)) face-on).
Eigen::Matrix<double, 2, 8> gapOfTips() {
  Eigen::Matrix<double, 2, 8> G = Eigen::Matrix<double, 2, 8>::Zero();
  for (int i = 0; i < 2; ++i) {
    G(i, i) = G(i, 2 + i) = 0.5;
    G(i, 4 + i) = G(i, 6 + i) = -0.5;
  }
  return G;
}

}  // namespace

Eigen::Vector2d membraneTensions(const HandController& hand, const HandJoints& q, const Vec2& box,
                                 double angle, Eigen::Matrix<double, 2, 6>* dq,
                                 Eigen::Matrix2d* dbox) {
  // l = |cA - a| + |rB - rA| + |b - cB| with the corners c = box + R r
  // (docs/model.md#rotating-box); T = k max(0, l - L).
  const std::vector<BoxCable> cables = hand.boxCables(q);
  const FingertipJacobian tipJacobian = fingertipJacobian(hand.model(), q);
  Eigen::Vector2d T;
  for (int f = 0; f < 2; ++f) {
    const BoxCable& c = cables[f];
    const Vec2 cA = box + rotate(c.cornerA, angle), cB = box + rotate(c.cornerB, angle);
    const Vec2 uA = (c.a - cA).normalized(), uB = (c.b - cB).normalized();
    const double length = (c.a - cA).norm() + (c.cornerB - c.cornerA).norm() + (c.b - cB).norm();
    const bool taut = length > c.L;
    T[f] = taut ? c.k * (length - c.L) : 0.0;
    Eigen::Matrix<double, 1, 8> dTips = Eigen::Matrix<double, 1, 8>::Zero();
    if (taut) dTips.segment<2>(4 * f) = c.k * uA, dTips.segment<2>(4 * f + 2) = c.k * uB;
    if (dq) dq->row(f) = dTips * tipJacobian;
    if (dbox) dbox->row(f) = taut ? Vec2(-c.k * (uA + uB)) : Vec2::Zero();
  }
  return T;
}

MpcPrediction predictHorizon(const HandModel& m, const HandMpcParams& p,
                             const MpcLinearisation& lin, const HandJoints& commanded) {
  const int N = p.horizon, n = 6 * N;
  const double h = p.period / kMpcSubsteps;
  const double follow = 1 - std::exp(-h / mpcServoLag(m));
  const double c = m.boxMass * m.boxDamping;  // N s/m: the table's drag
  const Eigen::Matrix2d inverse =
      ((m.boxMass + h * c) * Eigen::Matrix2d::Identity() + h * h * lin.stiffness).inverse();
  AffineState s;
  s.joints = Eigen::MatrixXd::Zero(6, n + 1);
  s.box = Eigen::MatrixXd::Zero(2, n + 1);
  s.velocity = Eigen::MatrixXd::Zero(2, n + 1);
  s.joints.col(0) = lin.joints;
  s.box.col(0) = lin.box;
  s.velocity.col(0) = lin.velocity;
  // The equilibrium the box follows: e(q) + d + J (q' - q), affine in the joints' affine state.
  Eigen::MatrixXd before = Eigen::MatrixXd::Zero(6, n + 1);  // targets at the update's start
  before.col(0) = commanded;
  MpcPrediction out;
  for (int k = 0; k < N; ++k) {
    Eigen::MatrixXd after = before;
    after.block<6, 6>(0, 1 + 6 * k) += Eigen::Matrix<double, 6, 6>::Identity();
    for (int i = 1; i <= kMpcSubsteps; ++i) {
      // The servo targets ramp over the update (hand_grasp.h); the joints follow with the
      // servos' lag and sit their droop off the targets.
      Eigen::MatrixXd ramp = before + (after - before) * (double(i) / kMpcSubsteps);
      ramp.col(0) += lin.droop;
      s.joints += follow * (ramp - s.joints);
      Eigen::MatrixXd equilibrium = lin.jacobian * s.joints;
      equilibrium.col(0) += lin.equilibrium - lin.jacobian * lin.joints;
      s.velocity = inverse * (m.boxMass * s.velocity + h * lin.stiffness * (equilibrium - s.box));
      s.box += h * s.velocity;
    }
    out.commanded.push_back(affine(after));
    out.joints.push_back(affine(s.joints));
    out.box.push_back(affine(s.box));
    out.velocity.push_back(affine(s.velocity));
    // The angle sits at its equilibrium at the predicted joints (zero for a box that cannot turn).
    Eigen::MatrixXd angle = lin.angleJacobian * s.joints;
    angle(0, 0) += lin.angleEquilibrium - lin.angleJacobian.dot(lin.joints);
    out.angle.push_back(affine(angle));
    before = after;
  }
  return out;
}

HandMpc::HandMpc(HandModel model, HandMpcParams params)
    : params_(params), hand_(std::move(model)) {}

void HandMpc::reset() {
  started_ = false;
  offset_.setZero();
  plan_.resize(0);
  status_ = {};
}

MpcLinearisation HandMpc::linearise(const HandJoints& q, const Vec2& box, const Vec2& velocity,
                                    const HandJoints& commanded, double angle) {
  const HandModel& m = hand_.model();
  // The servo model: what the joints would be without load, to read their droop off. A command
  // that is not the one this controller last asked for (a re-grasp) restarts it.
  const bool fresh = !started_ || (commanded - expectedCommanded_).cwiseAbs().maxCoeff() > 1e-9;
  if (fresh) {
    servo_ = previousCommanded_ = commanded;
    offset_.setZero();
    angleOffset_ = 0;
    plan_.resize(0);
  } else {
    const double h = params_.period / kMpcSubsteps;
    const double follow = 1 - std::exp(-h / mpcServoLag(m));
    for (int i = 1; i <= kMpcSubsteps; ++i)
      servo_ += follow * (previousCommanded_ +
                          (commanded - previousCommanded_) * (double(i) / kMpcSubsteps) - servo_);
    previousCommanded_ = commanded;
  }
  MpcLinearisation lin;
  lin.joints = q;
  lin.droop = q - servo_;
  lin.box = box;
  lin.velocity = velocity;
  if (!m.turn) angle = 0;
  const BoxPrediction p = hand_.predict(q, box, angle);
  if (!p.smooth) return lin;
  lin.jacobian = p.jacobian;
  lin.stiffness = p.stiffness;
  lin.tips = fingertipJacobian(m, q);
  lin.faceOn = m.turn ? faceOnTerms(m, fingertipPoints(m, q), box, angle)
                      : faceOnTerms(m, fingertipPoints(m, q), box);
  lin.tension = membraneTensions(hand_, q, box, angle, &lin.tensionJoints, &lin.tensionBox);
  // The model's offset: where the box rests against where the statics puts it. At rest the box
  // sits at e + d; moving, it lags e by K^-1 c v, which is taken off.
  const double drag = m.boxMass * m.boxDamping;
  const Vec2 seen = box + lin.stiffness.ldlt().solve(drag * velocity) - p.box;
  if (fresh)
    offset_ = seen;
  else if (velocity.norm() < params_.restSpeed)
    offset_ += params_.offsetGain * (seen - offset_);
  lin.equilibrium = p.box + offset_;
  if (m.turn) {  // the angle's offset the same way (the table damps the turning as the sliding)
    const double seenAngle = angle - p.angle;
    if (fresh)
      angleOffset_ = seenAngle;
    else if (velocity.norm() < params_.restSpeed)
      angleOffset_ += params_.offsetGain * (seenAngle - angleOffset_);
    lin.angle = angle;
    lin.angleEquilibrium = p.angle + angleOffset_;
    lin.angleJacobian = p.angleJacobian;
  }
  lin.valid = true;
  started_ = true;
  return lin;
}

HandJoints HandMpc::update(const HandJoints& q, const BoxPose& boxPose, const Vec2& velocity,
                           const BoxPose& targetPose, const HandJoints& commanded) {
  const auto start = std::chrono::steady_clock::now();
  const HandModel& m = hand_.model();
  const HandMpcParams& p = params_;
  const int N = p.horizon, n = 6 * N;
  const Vec2 box = boxPose.head<2>(), target = targetPose.head<2>();
  const bool turn = m.turn;
  const double targetAngle = turn ? targetPose[2] : 0;
  const MpcLinearisation lin = linearise(q, box, velocity, commanded, boxPose[2]);
  status_ = {};
  expectedCommanded_ = commanded;
  if (!lin.valid) {
    status_.solveMicros =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    return HandJoints::Zero();
  }
  const MpcPrediction pred = predictHorizon(m, p, lin, commanded);

  // Cost 1/2 u^T H u + f^T u.
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  auto addSquare = [&](const Eigen::MatrixXd& A, const Eigen::VectorXd& residual, double w) {
    H.noalias() += w * A.transpose() * A;
    f.noalias() += w * A.transpose() * residual;
  };
  const Eigen::Matrix<double, 2, 8> gapTips = gapOfTips();
  // The pinch's gap, turned with a box that turns: R(a) g, linear in the predicted angle a about
  // the measured one.
  const Vec2 pinchGap(0, 2 * (m.baseY - m.paddleOffset));
  const Vec2 gapAt = turn ? rotate(pinchGap, lin.angle) : pinchGap, gapTurn = perp(gapAt);
  const Vec2 gapNow = gapTips * fingertipPoints(m, q) - gapAt;
  const Eigen::Matrix<double, 2, 6> gapJoints = gapTips * lin.tips;
  for (int k = 0; k < N; ++k) {
    addSquare(pred.box[k].slope, pred.box[k].offset - target, 1.0);
    // The gap and the tilt of the predicted joints, linear about the measured ones.
    const MpcAffine &joints = pred.joints[k], &angle = pred.angle[k];
    Eigen::MatrixXd gap = gapJoints * joints.slope;
    Eigen::Vector2d gap0 = gapNow + gapJoints * (joints.offset - q);
    if (turn) {
      gap -= gapTurn * angle.slope;
      gap0 -= gapTurn * (angle.offset[0] - lin.angle);
      addSquare(angle.slope, angle.offset - Eigen::VectorXd::Constant(1, targetAngle),
                p.angleArm * p.angleArm);
    }
    addSquare(gap, gap0, p.gapWeight);
    for (int fgr = 0; fgr < 2; ++fgr) {  // face-on: the paddle turned as the box
      Eigen::RowVectorXd tilt =
          joints.slope.row(3 * fgr + kProximal) + joints.slope.row(3 * fgr + kDistal);
      double tilt0 = joints.offset[3 * fgr + kProximal] + joints.offset[3 * fgr + kDistal];
      if (turn) tilt -= angle.slope, tilt0 -= angle.offset[0];
      addSquare(tilt, Eigen::VectorXd::Constant(1, tilt0), p.tiltWeight);
    }
  }
  addSquare(pred.velocity[N - 1].slope, pred.velocity[N - 1].offset, p.settleWeight);
  H.diagonal().array() += p.effort;

  // Constraints C u >= b. A condition already failing now need only not get worse.
  const int rows = N * (12 + 12 + 12 + 12 + 4 + 4);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(rows, n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(rows);
  int r = 0;
  auto atLeast = [&](const Eigen::RowVectorXd& row, double offset, double bound) {
    C.row(r) = row, b[r++] = bound - offset;
  };
  const Eigen::Matrix<double, 12, 6> faceJoints = lin.faceOn.dTips * lin.tips;
  // The membranes' damping adds b_s dl/dt = (b_s / k_s) dT/dt to their tension: a membrane
  // shortened fast goes slack however taut it sits (b_s / k_s = 3.7 s: 1 N of static tension lost
  // within one update takes 69 N off). Bounded is the static tension plus that share of its
  // change over each update.
  const double damping = m.damping / m.stiffness / p.period;
  MpcAffine previousTension{lin.tension, Eigen::MatrixXd::Zero(2, n)};
  for (int k = 0; k < N; ++k) {
    const MpcAffine &cmd = pred.commanded[k], &joints = pred.joints[k], &at = pred.box[k];
    for (int j = 0; j < 6; ++j) {
      const double rate = (j % 3 == kSlide ? p.slideRate : p.revoluteRate) * p.period;
      Eigen::RowVectorXd unit = Eigen::RowVectorXd::Zero(n);
      unit[6 * k + j] = 1;
      atLeast(unit, 0, -rate), atLeast(-unit, 0, -rate);
      atLeast(cmd.slope.row(j), cmd.offset[j], m.lower[j]);
      atLeast(-cmd.slope.row(j), -cmd.offset[j], -m.upper[j]);
      atLeast(joints.slope.row(j), joints.offset[j], std::min(m.lower[j] + p.limitMargin, q[j]));
      atLeast(-joints.slope.row(j), -joints.offset[j], -std::max(m.upper[j] - p.limitMargin, q[j]));
    }
    // The box no faster than the model still holds: the membranes' lag and the servos' grow with
    // the speed, and the linear model knows neither limit.
    for (int i = 0; i < 2; ++i) {
      const MpcAffine& v = pred.velocity[k];
      atLeast(v.slope.row(i), v.offset[i], std::min(-p.maxSpeed, lin.velocity[i]));
      atLeast(-v.slope.row(i), -v.offset[i], std::min(-p.maxSpeed, -lin.velocity[i]));
    }
    // Face-on at the predicted joints and box (and its angle).
    Eigen::MatrixXd face = faceJoints * joints.slope + lin.faceOn.dBox * at.slope;
    Eigen::VectorXd face0 =
        lin.faceOn.value + faceJoints * (joints.offset - q) + lin.faceOn.dBox * (at.offset - box);
    if (turn) {
      face += lin.faceOn.dAngle * pred.angle[k].slope;
      face0 += lin.faceOn.dAngle * (pred.angle[k].offset[0] - lin.angle);
    }
    for (int i = 0; i < 12; ++i)
      atLeast(face.row(i), face0[i], std::min(p.wrapMargin, lin.faceOn.value[i]));
    const MpcAffine staticTension{
        lin.tension + lin.tensionJoints * (joints.offset - q) + lin.tensionBox * (at.offset - box),
        lin.tensionJoints * joints.slope + lin.tensionBox * at.slope};
    const Eigen::MatrixXd tension =
        staticTension.slope + damping * (staticTension.slope - previousTension.slope);
    const Eigen::Vector2d tension0 =
        staticTension.offset + damping * (staticTension.offset - previousTension.offset);
    previousTension = staticTension;
    for (int fgr = 0; fgr < 2; ++fgr) {
      atLeast(tension.row(fgr), tension0[fgr], std::min(p.minTension, lin.tension[fgr]));
      atLeast(-tension.row(fgr), -tension0[fgr], -std::max(p.maxTension, lin.tension[fgr]));
    }
  }

  // Warm start: the last plan one update on (its last step repeated as zero).
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n);
  if (plan_.size() == n) x0.head(n - 6) = plan_.tail(n - 6);
  const SmallQpResult qp = solveSmallQp(H, f, C, b, x0, p.maxIterations);
  plan_ = qp.x;
  status_.planned = true;
  status_.iterations = qp.iterations;
  status_.slack = qp.slack;
  for (int k = 0; k < N; ++k) status_.plannedBox.push_back(pred.box[k].at(qp.x));
  // Where the constraints cannot all be met the solver relaxes them all alike; the joints' rates
  // and limits hold regardless (the step applied is clipped to them).
  HandJoints dq = qp.x.head<6>();
  for (int j = 0; j < 6; ++j) {
    const double rate = (j % 3 == kSlide ? p.slideRate : p.revoluteRate) * p.period;
    dq[j] = std::clamp(dq[j], -rate, rate);
  }
  dq = m.clamp(commanded + dq) - commanded;
  expectedCommanded_ = commanded + dq;
  status_.solveMicros =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  return dq;
}

double measureMpcUpdateMicros(int repeats, int horizon) {
  HandMpcParams params;
  params.horizon = horizon;
  HandMpc mpc{HandModel{}, params};
  const HandController hand{HandModel{}};
  const HandJoints q = HandJoints::Zero();
  const Vec2 box = hand.predict(q, Vec2::Zero()).box;
  std::vector<double> micros;
  for (int i = 0; i < std::max(1, repeats); ++i) {
    mpc.reset();  // the same first update each time: the pinch, a target 10 cm off
    mpc.update(q, BoxPose(box.x(), box.y(), 0), Vec2::Zero(), BoxPose(0.1, 0.05, 0), q);
    micros.push_back(mpc.status().solveMicros);
  }
  std::nth_element(micros.begin(), micros.begin() + micros.size() / 2, micros.end());
  return micros[micros.size() / 2];
}

}  // namespace cablelab
