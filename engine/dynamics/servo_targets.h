// The targets the joints' servos aim at over a step (docs/servos.md, "Targets set between steps").
// A target set between steps (set_servo_target, the hand's controller) is reached over the step:
// the servo sees it move on linearly across the step's sub-steps, reaching it at the step's end,
// as a speed servo's target moves on. Set in one jump at the first sub-step, a servo stiff enough
// to follow it within that sub-step whipped its joint through the whole jump and threw what it
// lifted (a light drum at 20 Hz x 7: its weight thrown to the drum at 8 m/s by a ramp that asked
// 1.35 m/s). With one sub-step nothing changes. World's.
#pragma once

#include <span>
#include <vector>

#include "engine/model/scene.h"

namespace cablelab {

class ServoTargets {
 public:
  /// The scene's joints: their servos' targets (rad or m) and speeds (rad / s or m / s).
  /// `start`: where each joint starts (rad or m), from which the first step moves its target on
  /// to the scene's, as one set before it (a step written in the scene file); empty: the scene's
  /// targets hold from the start (a scene written mid-run).
  void reset(std::span<const JointDef> joints, std::span<const double> start = {});

  /// The target set for joint i (rad or m): the one its servo reaches at the step's end.
  double operator[](size_t i) const { return set_[i]; }
  /// Sets joint i's target, reached over the next step.
  void set(size_t i, double target) { set_[i] = target; }
  /// Sets joint i's target and puts its servo there now (a pose holds its joints where it left
  /// them: the next step has no way to go).
  void hold(size_t i, double target) { set_[i] = from_[i] = target; }
  /// The bodies were moved or their velocities set: the targets set for the next step take
  /// effect at once (the user places the joints where they sent the servos, the hand's start).
  void jump() { jumped_ = true; }

  /// Sub-step s of n (0-based) starts: targets() then holds each servo's target at its end.
  void beginSubstep(int s, int n);
  /// The targets of the current sub-step's end, each before its servo's speed over the piece
  /// being solved (rad or m; per joint).
  std::span<const double> targets() const { return now_; }
  /// A piece of `taken` seconds of the step is done: each target moves on at its speed.
  void moveOn(double taken);
  /// The step ended: its targets are reached (the next step starts from them).
  void endStep() { from_ = set_; }

 private:
  std::vector<double> set_;   // per joint: what the user set, moved on at the speed
  std::vector<double> from_;  // ... where the step started, moved on at the speed
  std::vector<double> now_;   // ... the current sub-step's end
  std::vector<double> speeds_;
  bool jumped_ = false;
};

}  // namespace cablelab
