// The sections inside the sandbox's two side panels (ui/panels.h places the panels).
//
// Needs: Dear ImGui with a window open (each function draws into the current window), a
// Sandbox. Every control has a tooltip (ui::tooltip).
#pragma once

#include "ui/panels.h"
#include "ui/sandbox.h"

namespace cablelab::ui {

/// A titled separator (ImGui 1.86 has no SeparatorText).
void section(const char* title);

/// Title, description, "what to try" and the built-in scene's parameters as sliders.
void scenePanel(Sandbox& sandbox);
/// Play, pause, step, reset, speed, screenshot and recording.
void runPanel(Sandbox& sandbox);
/// dt, substeps, gravity.
void integrationPanel(Sandbox& sandbox);
/// Camera, follow, draw toggles, tension scale, UI scale and projector mode, drag limit.
void viewPanel(Sandbox& sandbox);
/// The Inspector's contents: cables, selected body, engine warnings.
void inspectorContents(Sandbox& sandbox);
/// Side and grip of each pulley of scene cable `cable` (ui/inspector_edits.cpp).
void pulleyEdits(Sandbox& sandbox, int cable);
/// The joints: pick one, edit its limits, motor and servo.
void jointEdits(Sandbox& sandbox);
/// The log of what the engine reported (ui/log_panel.cpp).
void logSection(Sandbox& sandbox);

}  // namespace cablelab::ui
