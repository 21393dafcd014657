// The Simulation panel's Timeline row (ui/timeline.h): a slider over the kept 30 s and
// back / forward buttons; and the step-back key's action.
//
// Needs: Dear ImGui with a window open, a Sandbox.
#pragma once

#include "ui/sandbox.h"

namespace cablelab::ui {

/// The slider (moving it pauses and puts the world at that moment) and the step buttons.
void timelinePanel(Sandbox& sandbox);

/// The step-back key (b): pauses and goes one step back; says so when nothing older is kept.
void stepBack(Sandbox& sandbox);

}  // namespace cablelab::ui
