#include "engine/hand/hand_grasp.h"

#include <cmath>
#include <limits>

#include "engine/dynamics/world.h"
#include "engine/hand/hand_kinematics.h"

namespace cablelab {

Vec2 nearestPinch(const HandModel& m, const Vec2& g) {
  // Both fingers see the pinch centre from (baseX, 0) (their bases sit baseY off it, as do their
  // paddles): the pinch set is a sector about that point, limited by the proximal and distal
  // angles and the slide. Clamped in polar coordinates, a hair inside.
  const Vec2 d = g - Vec2(m.baseX, 0);
  const double margin = 1e-9;
  double angleLimit = std::numeric_limits<double>::infinity();
  for (int f = 0; f < 2; ++f) {
    angleLimit = std::min({angleLimit, m.upper[3 * f + kProximal], -m.lower[3 * f + kProximal],
                           m.upper[3 * f + kDistal], -m.lower[3 * f + kDistal]});
  }
  const double rLow = m.linkLength + std::max(m.lower[kSlide], m.lower[3 + kSlide]);
  const double rHigh = m.linkLength + std::min(m.upper[kSlide], m.upper[3 + kSlide]);
  const double angle =
      std::clamp(std::atan2(d.y(), d.x()), -angleLimit + margin, angleLimit - margin);
  const double r = std::clamp(d.norm(), rLow + margin, rHigh - margin);
  return Vec2(m.baseX, 0) + r * Vec2(std::cos(angle), std::sin(angle));
}

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
  for (int j = 0; j < 6; ++j) world.setServoTargetAtOnce(world.findJoint(kHandJointNames[j]), q[j]);
}

HandGrasp::HandGrasp(const HandModel& model, const HandControllerParams& params,
                     GraspOptions options)
    : model_(model), options_(options), controller_(model, params) {}

bool HandGrasp::attach(const World& world) {
  for (int j = 0; j < 6; ++j)
    if ((joints_[j] = world.findJoint(kHandJointNames[j])) < 0) return false;
  box_ = world.findBody(kHandBoxName);
  for (int f = 0; f < 2; ++f) cables_[f] = world.findCable(kHandCableNames[f]);
  return box_ >= 0 && cables_[0] >= 0 && cables_[1] >= 0;
}

HandJoints HandGrasp::joints(const World& world) const {
  HandJoints q;
  for (int j = 0; j < 6; ++j) q[j] = world.joint(joints_[j]).value;
  return q;
}

void HandGrasp::setServos(World& world, const HandJoints& q) const {
  // The controller's gains were tuned on targets taken at once (docs/servos.md).
  for (int j = 0; j < 6; ++j) world.setServoTargetAtOnce(joints_[j], q[j]);
}

void HandGrasp::startRamp(double t, const HandJoints& from, const HandJoints& to, double duration) {
  rampFrom_ = from;
  commanded_ = to;
  rampStart_ = t;
  rampEnd_ = t + duration;
}

void HandGrasp::begin(World& world, const Vec2& start) {
  const double t = world.time();
  pinchAt_ = start;
  const HandJoints pinch = pinchJoints(model_, start);
  // Swung apart as openPose() about the origin (whose pinch is q = 0), paddles kept face-on.
  const HandJoints open = model_.clamp(pinch + model_.openPose());
  placeHand(world, model_, open);
  world.setBodyTransform(box_, start, 0);
  world.setBodyVelocity(box_, Vec2::Zero(), 0);
  phase_ = Phase::Closing;
  closed_ = false;
  controlStart_ = std::numeric_limits<double>::infinity();
  controller_.reset();
  startRamp(t, open, model_.clamp(pinch), options_.closeTime);
  setServos(world, open);
}

void HandGrasp::beginPinched(const World& world) {
  const double t = world.time();
  pinchAt_ = world.body(box_).position;
  const HandJoints q = joints(world);
  startRamp(t, q, q, 0);
  phase_ = Phase::Control;
  closed_ = true;
  graspTime_ = t;
  controlStart_ = nextUpdate_ = t + options_.settleTime;
  controller_.reset();
  events_.push_back({t, "pinched"});
}

void HandGrasp::beforeStep(World& world, const std::optional<Vec2>& target, const GraspLaw& law) {
  const double t = world.time();
  const double period = controller_.params().period;
  if (phase_ == Phase::Lost && t >= phaseStart_ + options_.stopTime) {
    // Re-grasp about the box where it lies (or the nearest point the fingers can pinch).
    ++regrasps_;
    events_.push_back({t, "re-grasp"});
    pinchAt_ = nearestPinch(model_, world.body(box_).position);
    const HandJoints q = joints(world);
    phase_ = Phase::Opening;
    phaseStart_ = t;
    startRamp(t, q, model_.clamp(pinchJoints(model_, pinchAt_) + model_.openPose()),
              options_.openTime);
  }
  if (phase_ == Phase::Opening && t >= rampEnd_ - 1e-9) {
    phase_ = Phase::Closing;
    closed_ = false;
    controller_.reset();
    startRamp(t, commanded_, model_.clamp(pinchJoints(model_, pinchAt_)), options_.closeTime);
  }
  if (controlling(t) && t >= nextUpdate_ - 1e-9) {
    const HandJoints from = commanded_;
    if (law || target) {
      const HandJoints q = joints(world);
      const BodyState& box = world.body(box_);
      const HandJoints dq =
          law ? law(q, box.position, commanded_)
              : controller_.update(q, BoxPose(box.position.x(), box.position.y(), box.angle),
                                   BoxPose(target->x(), target->y(), targetAngle_), commanded_);
      ++updates_;
      // Spread over the period; no wind-up against the limits.
      startRamp(t, from, model_.clamp(commanded_ + dq), period);
    } else {
      startRamp(t, from, from, 0);
    }
    nextUpdate_ += period;
  }
  const double span = rampEnd_ - rampStart_;
  const double s = span > 0 ? std::clamp((t - rampStart_) / span, 0.0, 1.0) : 1.0;
  setServos(world, rampFrom_ + s * (commanded_ - rampFrom_));
}

std::string HandGrasp::lossReason(const World& world) const {
  for (int f = 0; f < 2; ++f) {
    const Cable& c = world.cable(cables_[f]);
    const std::string name = f == 0 ? "top" : "bottom";
    if (c.wraps() == 0) return name + " membrane unwrapped";
    if (c.slack()) return name + " membrane slack";
  }
  return "";
}

void HandGrasp::afterStep(const World& world) {
  const double t = world.time();
  if (phase_ == Phase::Closing && !closed_ && world.cable(cables_[0]).wraps() >= 2 &&
      world.cable(cables_[1]).wraps() >= 2) {
    closed_ = true;
    if (graspTime_ < 0) graspTime_ = t;
    events_.push_back({t, "grasp closed"});
    // Control begins once the closing ramp has finished and the squeeze has settled a little
    // (before that the membranes barely press and the statics model is ill-conditioned).
    controlStart_ = nextUpdate_ = std::max(t, rampEnd_ + options_.settleTime);
    phase_ = Phase::Control;
    return;
  }
  if (!closed_ || (phase_ != Phase::Control)) return;
  const std::string reason = lossReason(world);
  if (reason.empty()) return;
  ++losses_;
  closed_ = false;
  events_.push_back({t, reason});
  controller_.reset();
  const HandJoints q = joints(world);
  startRamp(t, q, q, 0);  // stop where the fingers are
  phaseStart_ = t;
  phase_ = regrasps_ < options_.maxRegrasps ? Phase::Lost : Phase::Failed;
  if (phase_ == Phase::Failed) events_.push_back({t, "gave up"});
}

}  // namespace cablelab
