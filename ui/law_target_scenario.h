// LawTargetScenario: `cablelab-gui hand --script target-mpc` (or `target-pid`), dispatched by
// ui/scenario_script.h. Picks the outer loop's law in the hand's controller panel with synthetic
// mouse clicks, through the normal event path ("plan ahead (MPC)"; or "react to the error" and
// the PID toggle), then clicks empty space in the view, 0.4 m right of the box's start, to set the
// box's target there, and runs
// until the box has stayed within 5 mm of it for half a second (or 12 s have passed). Reports the
// law the panel ended with, the target, and how long the box took; tests/ui/law_target_gui_test.cpp
// judges them.
//
// Needs: an SDL video subsystem (the sandbox's Window), the hand scene.
#pragma once

#include <SDL.h>

#include <string>

#include "ui/sandbox.h"

namespace cablelab::ui {

class LawTargetScenario {
 public:
  static constexpr const char* kMpc = "target-mpc";
  static constexpr const char* kPid = "target-pid";
  /// `mpc`: pick "plan ahead (MPC)", else the Jacobian controller with its integral term.
  LawTargetScenario(Uint32 windowId, bool mpc) : windowId_(windowId), mpc_(mpc) {}
  /// Called once per frame before events are polled; false when finished (`report` then set).
  bool beforeFrame(Sandbox& sandbox, int frame, std::string& report);

 private:
  /// Frames at, at + 1, at + 2: the pointer to `screen` (px), the left button down, up.
  void click(const Vec2& screen, int frame, int at);
  static Vec2 centreOf(const PanelRect& r);

  // Members, not file-scope constants: unity batches join this file with turn_target_scenario.
  static constexpr int kLawClick = 3, kPidClick = 7, kTargetClick = 40;  ///< frames of the clicks
  /// m: the target's x, right of the box's start (the origin) on its line, clear of the box (half
  /// side 0.25 m) and of the membranes, where a click lands on empty space; the same every law.
  static constexpr double kTargetX = 0.4;
  static constexpr double kWithin = 0.005;     ///< m
  static constexpr double kSettledFor = 0.5;   ///< s within kWithin before the run ends
  static constexpr double kLongestRun = 12.0;  ///< s after the target click

  Uint32 windowId_;
  bool mpc_;
  Vec2 target_ = Vec2::Zero();  ///< m: where the click in the view puts the target
  double clickedAt_ = -1;       ///< s: world time of the click in the view
  double enteredAt_ = -1;       ///< s: the box within 5 mm of the target since (-1: not now)
  double closest_ = 1e300;      ///< m: the box's smallest distance to the target
};

}  // namespace cablelab::ui
