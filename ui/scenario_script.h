// ScenarioScript: the sandbox's acceptance scenarios (`cablelab-gui --script NAME`), driven by
// synthetic SDL events through the normal event path, like InputScript. Each reports one JSON
// object on stdout with what it measured; the tests in tests/ui/gui_test.cpp judge the figures.
//
//   describe     one frame; reports the title and description the Scene panel showed
//   reset-scale  drags a body hard (raising the tensions), presses r; reports the tension
//                scale before, after the drag and after the reset, and the scene's expected one
//   rigid-drag   drags the body at the end of a rigid cable 3 m away from the cable for 2 s;
//                reports the largest stretch (length - rest length) of any taut rigid cable
//   drop-box     the hand: drags the box out of the membranes and lets go; reports the grasp
//                state the controller panel shows
//   capstan-slip the capstan: 1 s with its own masses (holds), then m_load = 6 as the Scene
//                panel's slider sets it (slips for 1 s); reports the Inspector's span table both
//                times with the engine's span tensions of the moment and the Inspector's row
//                overflow
//   pose-drag    Space (pause), drags the body at the end of a rigid cable 1 m straight out
//                along its last segment, releases, Space (play) and runs 0.1 s; reports the
//                cable's largest stretch while paused and at Play, how far the body went, the
//                energy posed and 0.1 s later, the body's top speed after Play, the status
//                line at the end of the drag and the guard banner at the end
//   pose-payout  the same with Shift held while dragging (the cable lets out length); reports
//                the cable's rest length before and after as well
//   author       builds a scene by clicks (a box, a pulley, a cable anchor -> pulley -> box),
//                saves it to --script-out; reports the counts and the file
//   build-...    a new scene, one element built by clicks and keys (ui/build_scenarios.h), saved
//                to --script-out; reports the counts and the error shown, then presses Space
//                and reports every body's pose after kBuildPlaySteps steps (what `cablelab run`
//                of the saved file must give at that step)
//   present, grasp-quiet, tension-run   the lecture-hall checks (ui/lecture_scripts.h)
//   turn-target  the hand with a box that turns: drags the target's angle handle
//                (ui/turn_target_scenario.h)
//   target-mpc, target-pid   the hand: picks the controller panel's law, clicks a target
//                (ui/law_target_scenario.h)
//
// Needs: an SDL video subsystem (the sandbox's Window), a Sandbox with a loaded scene.
#pragma once

#include <SDL.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ui/law_target_scenario.h"
#include "ui/lecture_scripts.h"
#include "ui/sandbox.h"
#include "ui/turn_target_scenario.h"

namespace cablelab::ui {

class TimelineScenario;  // ui/timeline_scenarios.h: rewind, plot-export

class ScenarioScript {
 public:
  /// The scenario names above.
  static const std::vector<std::string>& names();

  /// `out`: the file the author scenario saves.
  ScenarioScript(std::string name, Uint32 windowId, std::string out);

  /// Called once per frame before events are polled; false when the scenario has finished.
  bool beforeFrame(Sandbox& sandbox, int frame);
  /// One JSON object with the scenario's figures.
  std::string report() const { return report_; }

 private:
  void mouse(Uint32 type, const Vec2& screen, Uint8 button = SDL_BUTTON_LEFT);
  void key(SDL_Keycode key);
  bool describe(Sandbox& sandbox, int frame);
  bool resetScale(Sandbox& sandbox, int frame);
  bool rigidDrag(Sandbox& sandbox, int frame);
  bool dropBox(Sandbox& sandbox, int frame);
  bool author(Sandbox& sandbox, int frame);
  bool capstanSlip(Sandbox& sandbox, int frame);
  bool poseDrag(Sandbox& sandbox, int frame);
  bool build(Sandbox& sandbox, int frame);

  std::string name_, out_, report_ = "{}";
  Uint32 windowId_;
  int body_ = -1, cable_ = -1;
  Vec2 from_ = Vec2::Zero(), to_ = Vec2::Zero();    ///< px
  Vec2 start_ = Vec2::Zero(), end_ = Vec2::Zero();  ///< body position (m)
  double figures_[6] = {0, 0, 0, 0, 0, 0};
  std::string said_;  ///< the status line at a moment the scenario reports
  double largest_ = 0;
  size_t step_ = 0;        ///< build: the next step
  bool playing_ = false;   ///< build: saved, now playing
  double playFrom_ = 0;    ///< build: the world's time at Play (s)
  double restBefore_ = 0;  ///< pose scenarios: the cable's rest length before the drag (m)
  std::shared_ptr<TimelineScenario> timeline_;      ///< the rewind and plot scenarios
  std::unique_ptr<LectureScript> lecture_;          ///< the lecture-hall checks
  std::unique_ptr<TurnTargetScenario> turnTarget_;  ///< turn-target (ui/turn_target_scenario.h)
  std::unique_ptr<LawTargetScenario> lawTarget_;    ///< target-mpc, target-pid
  std::string bannerSeen_;                          ///< drop-box: a banner shown during the drag
};

}  // namespace cablelab::ui
