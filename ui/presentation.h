// Presentation mode and the fitted view: the sandbox in a lecture hall.
//
// One key (p, or View > presentation mode) hides the side panels; a slim strip stays at the top
// (the menus, Build among them, Play/Pause, Step, Reset and the scene's name, ui/panels.cpp)
// with the status line at the bottom, and the scene is fitted to the window: its moving bodies,
// cables, pulleys and the fixed bodies near them (a ground, ui/scene_bounds.h) fill the view
// above the bars' row. Out of it, and while a student builds (showsCanvas()), a fit shows the
// scene's own view, grown to hold the same.
//
// The view stays fitted while the user has not panned or zoomed it: when a panel opens, closes
// or is resized, the UI scale (projector mode) changes, the window is resized or another scene
// opens, it is fitted again. The fit key (v, or View > fit scene view) fits it at any time.
//
// A looping demo that is thin and tall (the wheel's Atwood machine, the winch, the tackle: a
// long rope under a small wheel) would be a sliver at a whole-run fit, a few percent of the
// window's width. Presentation mode shows it in close-up instead: the top of the mechanism (the
// wheel, drum or pulleys the rope hangs from) and the bodies hanging below it within the widest
// close-up (the capstan wound twice: its hold and its load), else the nearest, at least
// kCloseUpSpan times the scene's width tall; the view follows the run (zooms out as that body
// moves away, in and along smoothly when it comes nearer; never a jump). The close-up zooms out
// at most three times that: a body farther down from the start leaves the mechanism alone in
// view (the winch's load, until the drum winds it up); one the view followed there (the
// tackle's effort weight) holds the widest view until the run starts again.
//
// Needs: ui/sandbox.h (no SDL, no GL); the marker key's room in the fit is measured with the
// text font when an ImGui context has one.
#pragma once

#include "ui/sandbox.h"
#include "ui/scene_bounds.h"

namespace cablelab::ui {

/// True when presentation mode fits the scene's own view (its canvas) rather than its parts: while
/// a Build tool is chosen (the clicks go on the view, which holds still as the scene grows) and
/// while nothing moves in it yet (a new scene's ground alone).
bool showsCanvas(const Sandbox& sandbox);

/// Turns presentation mode on or off; the view is fitted again once the panels are laid out.
void togglePresentation(Sandbox& sandbox);

/// Fits the view again when it is due (a new scene, Sandbox::fitPending) or when the free area
/// or the UI scale changed since the last fit and the user has not moved the view since. Call
/// once a frame, after the panels are laid out.
void keepViewFitted(Sandbox& sandbox);

/// The height (px) of the bars' row at the bottom of the view (the colour bar's, else the scale
/// bar's), kept free of the scene by a fit (0 when neither is drawn).
float barRowHeight(const Sandbox& sandbox);

/// The camera that shows the scene's moving parts (and `stage`, a demo's whole run, when not
/// empty) as large as `area` (px) allows, with a margin, keeping `bottomReserve` px at the
/// bottom of the area for the colour bar's row.
/// The close-up's height, in units of the scene's width (ui/presentation.h's comment).
inline constexpr double kCloseUpSpan = 2.4;

/// True when presentation mode shows `sandbox`'s scene in close-up: a looping demo whose whole
/// run, fitted to the free area, would be narrower than kCloseUpBelow of its width.
bool wantsCloseUp(const Sandbox& sandbox);

/// What a close-up shows: a view `span` m tall with `focus` (m) at its middle, of a scene
/// `width` m wide.
struct CloseUpFrame {
  Vec2 focus = Vec2::Zero();
  double span = 0, width = 0;
  double least = 0, widest = 0;  ///< m: the nearest and the farthest a close-up zooms out
  double reach = 0;              ///< m: the view that holds `body` (0: none)
  int body = -1;                 ///< that body (-1: none)
  int nearest = -1;              ///< the nearest body hanging below the top (-1: none)
};

/// The close-up of the run as it is now: the top of the mechanism (the wheel, drum or pulleys
/// the rope hangs from) and the bodies hanging below it as far down as the widest close-up
/// reaches (`body`: the lowest of them), at least kCloseUpSpan times the scene's width tall.
/// With no body that near: the widest when the nearest is `followed` (the view zoomed out
/// after it in this run), else the mechanism alone.
CloseUpFrame closeUpFrame(const World& world, int followed = -1);

/// The close-up camera: closeUpFrame() fills the area above `bottomReserve`.
Camera closeUpCamera(const World& world, const Camera& camera, const PanelRect& area,
                     float bottomReserve, int followed = -1);

/// Moves a close-up view towards its focus (called once a frame, `seconds` since the last),
/// and remembers when it zoomed out after a hanging body (DemoRun::closeUpBody).
void followCloseUp(Sandbox& sandbox, double seconds);

/// The presentation fit of `sandbox`'s scene in the `free` area (px): fitToContent(), or its
/// close-up (closeUpCamera()), made smaller where the marker key would cover it: in the area
/// below the key's strip along the top or left of its column, whichever shows it larger, unless
/// that would take a tenth of the scene's size (a small window: the key gives way).
Camera presentationFit(const Sandbox& sandbox, const PanelRect& free);

/// Out of presentation mode: `fitted` (the scene's own view, grown to hold its moving parts)
/// moved so that the marker key's column, top right, keeps off the moving parts (the hand's box
/// and paddles, the capstan's drum at 1280x720 were under it): the scene slides left, else down
/// below the key, as far as `area` (px, above `bottomReserve`) holds it; unchanged when neither
/// clears the key.
Camera clearOfKey(const Sandbox& sandbox, const Camera& fitted, const PanelRect& area,
                  float bottomReserve);

Camera fitToContent(const World& world, const Camera& camera, const PanelRect& area,
                    float bottomReserve, const WorldBounds& stage = {});

}  // namespace cablelab::ui
