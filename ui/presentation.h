// Presentation mode and the fitted view: the sandbox in a lecture hall.
//
// One key (p, or View > presentation mode) hides the side panels; a slim strip stays at the top
// (the menus, Play/Pause, Step, Reset and the scene's name, ui/panels.cpp) with the status line
// at the bottom, and the scene is fitted to the window: its moving bodies, cables and pulleys
// (ui/scene_bounds.h) fill the view above the colour bar's row. Out of it, a fit shows the
// scene's own view, grown to hold the same.
//
// The view stays fitted while the user has not panned or zoomed it: when a panel opens, closes
// or is resized, the UI scale (projector mode) changes, the window is resized or another scene
// opens, it is fitted again. The fit key (v, or View > fit scene view) fits it at any time.
//
// Needs: ui/sandbox.h only (no SDL, no GL, no ImGui frame).
#pragma once

#include "ui/sandbox.h"
#include "ui/scene_bounds.h"

namespace cablelab::ui {

/// Turns presentation mode on or off; the view is fitted again once the panels are laid out.
void togglePresentation(Sandbox& sandbox);

/// Fits the view again when it is due (a new scene, Sandbox::fitPending) or when the free area
/// or the UI scale changed since the last fit and the user has not moved the view since. Call
/// once a frame, after the panels are laid out.
void keepViewFitted(Sandbox& sandbox);

/// The height (px) of the colour bar's row at the bottom of the view, kept free of the scene by
/// a presentation fit (0 when no colour bar is drawn).
float barRowHeight(const Sandbox& sandbox);

/// The camera that shows the scene's moving parts (and `stage`, a demo's whole run, when not
/// empty) as large as `area` (px) allows, with a margin, keeping `bottomReserve` px at the
/// bottom of the area for the colour bar's row.
Camera fitToContent(const World& world, const Camera& camera, const PanelRect& area,
                    float bottomReserve, const WorldBounds& stage = {});

}  // namespace cablelab::ui
