// TurnTargetScenario: `cablelab-gui hand --set turn=1 --script turn-target` (dispatched by
// ui/scenario_script.h). Drags the handle at the end of the target marker's arm
// (controller_panel.h) with synthetic mouse events, through the normal event path, from the box's
// angle to 0.25 rad, releases it, and lets the controller turn the box there. Reports the angle the
// drag set, the box's angle at the end and how long it took; tests/ui/gui_test.cpp judges them.
//
// Needs: an SDL video subsystem (the sandbox's Window), the hand scene with a box that may turn.
#pragma once

#include <SDL.h>

#include <string>

#include "ui/sandbox.h"

namespace cablelab::ui {

class TurnTargetScenario {
 public:
  static constexpr const char* kName = "turn-target";
  explicit TurnTargetScenario(Uint32 windowId) : windowId_(windowId) {}
  /// Called once per frame before events are polled; false when finished (`report` then set).
  bool beforeFrame(Sandbox& sandbox, int frame, std::string& report);

 private:
  Uint32 windowId_;
  Vec2 from_ = Vec2::Zero(), to_ = Vec2::Zero();  ///< px: the handle before and after the drag
  double dragged_ = 0;                            ///< rad: the target angle the drag left
  double settledAt_ = -1;                         ///< s: the box within 0.02 rad of it since
};

}  // namespace cablelab::ui
