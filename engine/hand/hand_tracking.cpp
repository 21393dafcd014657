#include "engine/hand/hand_tracking.h"

#include <array>
#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/hand/hand_kinematics.h"

namespace cablelab {

namespace {
constexpr double kStartOffsetMin = 0.05;  // m: the default start is at least this off the target
constexpr double kSettledWithin = 0.005;  // m: time_to_5mm's tolerance
constexpr double kAtLimit = 1e-3;         // rad or m: a joint this close to a limit has hit it
}  // namespace

Vec2 defaultStart(const Vec2& target) {
  return target.norm() < kStartOffsetMin ? Vec2(0.1, 0.1) : Vec2::Zero();
}

namespace {

/// Decides when a run's outcome is clear (EarlyStop).
class StopWatch {
 public:
  explicit StopWatch(const EarlyStop& o) : o_(o) {}
  /// After a controlled step at time t with error e; `resting`: the target no longer moves.
  /// `angleError`: the box angle's (0 for a box that cannot turn).
  bool done(double t, double e, double angleError, bool resting, bool& reached) {
    if (!o_.enabled) return false;
    if (first_) inside_ = bestTime_ = t, first_ = false;
    if (e >= o_.tolerance || angleError >= o_.angleTolerance || !resting) inside_ = t;
    if (t - inside_ >= o_.settledFor) return reached = true;
    if (e < best_ - std::max(o_.progress, o_.share * best_)) best_ = e, bestTime_ = t;
    return t - bestTime_ >= o_.stallFor;
  }

 private:
  EarlyStop o_;
  double inside_ = 0, best_ = 1e300, bestTime_ = 0;
  bool first_ = true;
};

}  // namespace

TrackResult runTracking(const TrackOptions& o, const HandModel& model,
                        const std::function<void(long, long)>& onStep) {
  World world(buildHandScene(model), "hand");
  const double dt = world.scene().dt;
  const int substeps = world.scene().substeps;
  const long steps = std::lround(o.time / dt);

  HandControllerParams params = o.controller;
  if (o.pid) params.ki = kHandPidKi;
  HandGrasp grasp(model, params, o.grasp);
  grasp.attach(world);
  grasp.setTargetAngle(o.targetAngle);
  const int box = grasp.boxBody();

  TrackResult result;
  result.start = o.start.value_or(defaultStart(o.target));
  grasp.begin(world, result.start);
  size_t nextChange = 0;
  Vec2 current = o.target;  // the constant target, or the latest change
  auto targetAt = [&](double t) -> Vec2 {
    while (nextChange < o.changes.size() && t >= o.changes[nextChange].t - 1e-9)
      current = o.changes[nextChange++].target;
    if (o.rampTime <= 0 || nextChange > 0) return current;
    const double t0 = grasp.controlStart();
    if (!std::isfinite(t0)) return result.start;
    return result.start + (o.target - result.start) * std::clamp((t - t0) / o.rampTime, 0.0, 1.0);
  };
  // The angle ramps with the centre (from the box's start angle, 0) and stays at its target
  // through later changes of the centre's target.
  auto targetAngleAt = [&](double t) {
    if (o.rampTime <= 0) return o.targetAngle;
    const double t0 = grasp.controlStart();
    if (!std::isfinite(t0)) return 0.0;
    return o.targetAngle * std::clamp((t - t0) / o.rampTime, 0.0, 1.0);
  };
  auto maxTension = [&] {
    return std::max(world.cable(grasp.membrane(0)).tension(),
                    world.cable(grasp.membrane(1)).tension());
  };

  result.samples.reserve(steps + 1);
  result.samples.push_back({0, targetAt(0), world.body(box).position, maxTension(),
                            world.body(box).position, targetAngleAt(0), world.body(box).angle});
  StopWatch watch(o.stop);
  double sumSquares = 0, angleSquares = 0;
  long controlledSteps = 0;
  bool started = false;
  // The outer-loop law, timed: the Jacobian controller's update (what beforeStep would call) or
  // the MPC's.
  HandMpcParams mpcParams = o.mpc;
  mpcParams.period = params.period;
  HandMpc mpc(model, mpcParams);
  Vec2 target = Vec2::Zero();
  double targetAngle = 0, solveSeconds = 0;
  int updates = 0;
  const GraspLaw law = [&](const HandJoints& q, const Vec2& at, const HandJoints& commanded) {
    const auto t0 = std::chrono::steady_clock::now();
    const BodyState& b = world.body(box);
    const BoxPose pose(at.x(), at.y(), b.angle), goal(target.x(), target.y(), targetAngle);
    const HandJoints dq = o.law == HandLaw::Mpc
                              ? mpc.update(q, pose, b.velocity, goal, commanded)
                              : grasp.controller().update(q, pose, goal, commanded);
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    solveSeconds += took, ++updates;
    result.maxSolveMicros = std::max(result.maxSolveMicros, 1e6 * took);
    return dq;
  };
  Vec2 towards = Vec2::Zero();  // unit vector from the box at control's start to the target
  double enteredAt = -1;        // time the box last came within 5 mm (-1: outside now)
  std::array<bool, 6> atLimit{};
  for (long s = 0; s < steps; ++s) {
    const double t = world.time();
    target = targetAt(t);
    if (!started && grasp.controlling(t)) {
      started = true;
      result.startError = (world.body(box).position - target).norm();
      result.startTension = maxTension();
      towards = (o.target - world.body(box).position).normalized();
    }
    targetAngle = targetAngleAt(t);
    grasp.setTargetAngle(targetAngle);
    grasp.beforeStep(world, target, law);
    world.step(dt, substeps);
    grasp.afterStep(world);
    const Vec2 now = targetAt(world.time());
    const Vec2 position = world.body(box).position;
    const double angle = world.body(box).angle, nowAngle = targetAngleAt(world.time());
    result.samples.push_back(
        {world.time(), now, position, maxTension(),
         started && o.law == HandLaw::Jacobian ? grasp.controller().status().expected : position,
         nowAngle, angle});
    if (onStep) onStep(s + 1, steps);
    if (!started) continue;
    result.maxTension = std::max(result.maxTension, result.samples.back().tension);
    const double e = (position - now).norm();
    sumSquares += e * e;
    if (e >= kSettledWithin)
      enteredAt = -1;
    else if (enteredAt < 0)
      enteredAt = world.time();
    result.overshoot = std::max(result.overshoot, (position - now).dot(towards));
    const HandJoints q = grasp.joints(world);
    for (int j = 0; j < 6; ++j) {
      const bool at = q[j] <= model.lower[j] + kAtLimit || q[j] >= model.upper[j] - kAtLimit;
      result.limitHits += at && !atLimit[j];
      atLimit[j] = at;
    }
    const double angleError = std::abs(angle - nowAngle);
    angleSquares += angleError * angleError;
    ++controlledSteps;
    const bool resting =
        (o.rampTime <= 0 || world.time() >= grasp.controlStart() + o.rampTime) &&
        nextChange == o.changes.size() &&
        (o.law == HandLaw::Mpc ||  // the MPC has no reference: it plans to the target itself
         ((grasp.controller().status().reference - now).norm() < 1e-9 &&
          std::abs(grasp.controller().status().angleReference - (model.turn ? nowAngle : 0.0)) <
              1e-9));
    bool reached = false;
    if (!grasp.held() || watch.done(world.time(), e, angleError, resting, reached)) {
      result.stoppedEarly = o.stop.enabled && s + 1 < steps;
      if (o.stop.enabled) break;
    }
  }
  const TrackSample& last = result.samples.back();
  result.finalError = (last.box - last.target).norm();
  result.rmsError =
      controlledSteps > 0 ? std::sqrt(sumSquares / controlledSteps) : result.finalError;
  result.finalAngleError = std::abs(last.angle - last.targetAngle);
  result.rmsAngleError =
      controlledSteps > 0 ? std::sqrt(angleSquares / controlledSteps) : result.finalAngleError;
  result.timeTo5mm = started && enteredAt >= 0 ? enteredAt - grasp.controlStart() : -1;
  result.solveMicros = updates > 0 ? 1e6 * solveSeconds / updates : 0;
  result.graspTime = grasp.graspTime();
  result.graspHeld = grasp.graspTime() >= 0 && grasp.held();
  result.losses = grasp.losses();
  result.reached = result.graspHeld && result.finalError < o.stop.tolerance &&
                   result.finalAngleError < o.stop.angleTolerance;
  result.finalJoints = readHandJoints(world);
  result.events = grasp.events();
  return result;
}

}  // namespace cablelab
