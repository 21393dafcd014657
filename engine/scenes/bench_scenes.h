// Timing of whole World steps, for `cablelab bench` and tests/bench/scene_bench.cpp.
//
// Every figure is a median over individually timed steps (steady_clock) after a warm-up, so a
// preempted step on a shared machine does not move it. "Without cables" is the same SceneDef
// with its cables (and so its membranes) removed: the bodies, joints, servos and contacts are
// then stepped by Box2D alone through the same World::step() (sleeping is off in World).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/model/scene.h"

namespace cablelab {

struct StepTiming {
  int steps = 0;              ///< timed steps (after the warm-up)
  double stepMicros = 0;      ///< median wall time of World::step (us)
  double cableMicros = 0;     ///< median of StepStats::cableMicros (us): cable update + solve
  double meanWrapPoints = 0;  ///< wrap points in use, mean over the timed steps
  double wrapPointNanos = 0;  ///< median over steps of cableMicros / wrap points (ns), 0 if none
  double substepWrapPointNanos = 0;  ///< the same per sub-step (ns)
  /// Per cable, the tension of each span (N) after the last timed step: a cable that wheels
  /// grip has one per span, any other one.
  std::vector<std::pair<std::string, std::vector<double>>> spanTensions;
};

/// Steps a World built from `scene` `warmup` times, then times `steps` steps of scene.dt with
/// scene.substeps. `withCables == false` removes every cable first. Throws like World.
StepTiming measureSceneSteps(SceneDef scene, bool withCables, int warmup, int steps);

/// Both variants of one scene and the cable overhead (with / without - 1).
struct SceneTiming {
  std::string scene;
  StepTiming withCables, withoutCables;
  double overhead = 0;
};

/// Runs the two variants side by side: each of `rounds` rounds builds both worlds anew, warms
/// them up and steps them in alternating batches of 10 steps (so drift in the machine's speed
/// hits both alike); medians over all rounds.
SceneTiming measureScene(const SceneDef& scene, int warmup, int steps, int rounds = 5);

}  // namespace cablelab
