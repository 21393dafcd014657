#include "engine/hand/hand_controller.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>

#include "engine/statics/box_reduction.h"
#include "engine/statics/statics_sensitivity.h"

namespace cablelab {

HandController::HandController(HandModel model, HandControllerParams params)
    : model_(std::move(model)), params_(params) {}

StaticsProblem HandController::staticsProblem(const HandJoints& q, const Vec2& guess) const {
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
  return reduceBoxToPoint(cables, guess);
}

BoxPrediction HandController::predict(const HandJoints& q, const Vec2& guess) const {
  BoxPrediction out;
  const StaticsProblem problem = staticsProblem(q, guess);
  StaticsResult eq;
  solveStatics(problem, eq);
  out.box = eq.p;
  if (!eq.converged) return out;
  const StaticsSensitivity s = staticsSensitivity(problem, eq.p);
  if (s.kind != StaticsSensitivity::Kind::Smooth) return out;
  // The shift of figure 4-2 is a constant offset, so d p / d(shifted) = d p / d(fingertips).
  out.jacobian = s.dp * fingertipJacobian(model_, q);
  out.valid = wrapsFaceOn(model_, fingertipPoints(model_, q), eq.p);
  return out;
}

HandJoints HandController::update(const HandJoints& q, const Vec2& box, const Vec2& target,
                                  const HandJoints& commanded) {
  // The box's change over the last period (zero on the first update).
  const Vec2 change = hasPrevious_ ? Vec2(box - previousBox_) : Vec2::Zero();
  previousBox_ = box;
  hasPrevious_ = true;
  last_ = predict(q, box);
  // Outside the model's validity (a membrane no longer wraps a face, or the statics is not
  // smooth there): keep steering with the last valid Jacobian; the null-space task below brings
  // the grasp back to the pinch geometry.
  if (last_.valid) steering_ = last_.jacobian, hasSteering_ = true;
  if (!hasSteering_) return HandJoints::Zero();
  Vec2 error = box - target;
  // Conditional integration (anti-windup): the integral only collects the small residual offset
  // near the target, never the large transient of the grasp or of a ramp the box lags behind.
  if (error.norm() < params_.integralZone) integral_ += error * params_.period;
  if (error.norm() > params_.maxError) error *= params_.maxError / error.norm();
  const Vec2 command = params_.kp * error + params_.kd * change + params_.ki * integral_;
  const BoxJacobian& J = steering_;
  HandJoints winv = HandJoints::Ones();
  winv[kDistal] = winv[3 + kDistal] = 1.0 / params_.distalWeight;
  const Eigen::Matrix<double, 6, 2> JWt = winv.asDiagonal() * J.transpose();
  const Eigen::Matrix2d JWJt =
      J * JWt + params_.lambda * params_.lambda * Eigen::Matrix2d::Identity();
  const Eigen::Matrix<double, 6, 2> pinv = JWt * JWJt.inverse();
  // Secondary task: h(q) = sum tilt^2 + |D_top - D_bottom - (0, 2 baseY)|^2 (paddles face-on, the
  // pinch's squeeze kept), descended in the null space of the primary task.
  HandJoints gradient = HandJoints::Zero();
  // On the commanded targets, not the measured joints: the servos lag under load and a task on
  // the measured joints would wind up.
  const FingerPose top = fingerPose(model_, commanded, 0),
                   bottom = fingerPose(model_, commanded, 1);
  const Vec2 gap = top.paddle - bottom.paddle - Vec2(0, 2 * model_.baseY);
  for (int f = 0; f < 2; ++f) {
    const FingerPose& pose = f == 0 ? top : bottom;
    const double sign = f == 0 ? 1.0 : -1.0;
    const double tilt = commanded[3 * f + kProximal] + commanded[3 * f + kDistal];
    gradient[3 * f + kProximal] = tilt + sign * gap.dot(perp(pose.paddle - pose.link));
    gradient[3 * f + kSlide] =
        sign * gap.dot(Vec2(std::cos(pose.linkAngle), std::sin(pose.linkAngle)));
    gradient[3 * f + kDistal] = tilt;
  }
  const HandJoints faceOn = -params_.faceOnGain * winv.asDiagonal() * gradient;
  const Eigen::Matrix<double, 6, 6> nullspace = Eigen::Matrix<double, 6, 6>::Identity() - pinv * J;
  return -pinv * command + nullspace * faceOn;
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
