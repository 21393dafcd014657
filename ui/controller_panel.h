// Controller hook: the hand's controller panel and its per-step update, kept in one file so
// the controller can be wired in without touching the rest of the sandbox.
//
// Needs: ui/sandbox.h and Dear ImGui (a frame in progress for the panel). The sandbox calls
// drawControllerPanel() inside its Simulation window every frame, and controllerBeforeStep()
// before every World::step(). The target the user clicks is `sandbox.target` (world metres).
#pragma once

#include "engine/world.h"
#include "ui/sandbox.h"

namespace cablelab::ui {

/// ImGui widgets for the controller (gains, mode, grasp); called inside an open window.
void drawControllerPanel(Sandbox& sandbox);

/// Applies the controller to `world` before a step (servo targets, forces).
void controllerBeforeStep(Sandbox& sandbox, World& world);

}  // namespace cablelab::ui
