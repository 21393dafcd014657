// Demos that stay in view and keep going. Several built-in scenes are one run that ends: in
// `pulley` a body reaches its pulley at 2.7 s and everything stops; the tackle jams at the top
// at 3.7 s; the ballast comes to rest in under 2 s; the wheel's Atwood machine and the winch
// end with a body at the wheel or drum. Such a scene starts again 1 s after its run ends (it has
// moved and everything has been at rest since, or a body has gone far off its stage), so that a
// lecture can let it play. And the view holds the whole run: a probe run at open (no user
// input) finds the stage its moving parts cover, and the fitted view is grown to hold it (the
// tackle's effort weight no longer sinks off screen).
//
// Needs: the engine's World, ui/scene_bounds.h. Scene files and edited scenes never loop (a
// student's own mechanism stops where it stops) and have no stage: their view holds what they
// show now.
#pragma once

#include <string>

#include "engine/dynamics/world.h"
#include "ui/scene_bounds.h"

namespace cablelab::ui {

/// Seconds of the probe run that finds a scene's stage.
inline constexpr double kStageProbeSeconds = 8.0;
/// Seconds at rest (or off the stage) after which a looping scene starts again.
inline constexpr double kRunEndSeconds = 1.0;

struct DemoRun {
  bool loops = false;   ///< this scene starts again when its run ends
  WorldBounds stage;    ///< m: where the moving parts go over an undisturbed run
  bool moved = false;   ///< something moved in this run
  double endedFor = 0;  ///< s the run has looked ended (at rest after moving, or off the stage)
  int restarts = 0;     ///< runs started again since the scene opened
  /// The body hanging below the mechanism that presentation mode's close-up last zoomed out
  /// after in this run (-1: none): past the widest close-up it holds the widest for it
  /// (ui/presentation.h).
  int closeUpBody = -1;
};

/// Whether the built-in scene `name` is a run that ends, and so loops.
bool demoLoops(const std::string& name);

/// A new scene's DemoRun: whether it loops and, if it does, its stage from a probe run of
/// `scene` for kStageProbeSeconds (a run that fails keeps the stage found so far).
DemoRun startDemo(const SceneDef& scene, const std::string& name);

/// Called after every step of a looping scene: true once its run has looked ended for
/// kRunEndSeconds (then the caller resets the world and counts a restart).
bool runEnded(DemoRun& run, const World& world, double dt);

}  // namespace cablelab::ui
