// Renderer: draws a cablelab World with legacy (compatibility-profile) OpenGL.
//
// Needs: a current OpenGL context with the fixed-function pipeline (OpenGL 2.1 or a 3.x/4.x
// compatibility profile), glViewport covering camera.width x camera.height, and, when `text`
// is not null, a Dear ImGui frame in progress (labels go into that draw list; the platform
// renders ImGui after the scene). It links no GL library itself: the same object code runs in
// the SDL2 window (libGL) and in the OSMesa offscreen context (libOSMesa); see ui/README.md.
//
// What it draws, back to front: background and grid; bodies (filled shapes and outlines,
// coloured by type: static grey-green, kinematic blue, dynamic orange); polygon pulleys
// (orange outline) and point pulleys (rings), faded while their cable is off them; joints;
// cables coloured by tension (slack segments dashed grey); wrap points; the overlay (targets,
// arrows, text); then in screen space the tension legend (colour bar with numbers) and the
// scale bar. The renderer is stateless: the same world, camera and options give the same pixels.
#pragma once

#include "engine/dynamics/world.h"
#include "ui/camera.h"
#include "ui/overlay.h"

struct ImDrawList;

namespace cablelab::ui {

struct RenderOptions {
  /// Tension (N) at the top of the colour bar; <= 0: the largest current tension, rounded up
  /// to 1, 2 or 5 times a power of ten.
  double tensionScale = 0;
  int selectedBody = -1;      ///< highlighted body, -1 none
  int selectedCable = -1;     ///< highlighted cable, -1 none
  bool grid = true;           ///< grid lines and scale bar
  bool legend = true;         ///< tension colour bar and cable list
  bool wrapPoints = true;     ///< squares at wrap points, circles at anchors
  bool labels = true;         ///< body names
  bool tensions = true;       ///< cables coloured by tension (else one plain colour)
  bool forces = false;        ///< arrows of the cable forces at the anchors, length per newton
  bool markerLegend = false;  ///< a key of the markers drawn (the sandbox turns it on)
  /// Pixels to keep clear at the top of the free area for the marker key (a collapsed panel's
  /// title bar there).
  float keyTop = 0;
  /// Line widths and marker sizes are multiplied by this (projector mode: 2).
  float lineScale = 1;
  /// Cables drawn with an overstretch mark (rigid: longer than rest by > kOverstretch).
  bool overstretch = true;
  /// Screen rectangle (px, top-left origin) free of UI panels, where the legend and scale bar
  /// go; a zero-size rectangle means the whole viewport.
  float freeX = 0, freeY = 0, freeWidth = 0, freeHeight = 0;
  /// Clear and draw only inside the free rectangle (GL scissor): the sandbox's panels cover the
  /// rest, and on a software rasteriser every pixel drawn under them is time lost.
  bool clipToFree = false;
};

/// A rigid cable longer than its rest length by more than this (m) is drawn as overstretched.
inline constexpr double kOverstretch = 0.01;
/// An elastic cable stretched beyond this share of its rest length is drawn as overstretched.
inline constexpr double kOverstretchElastic = 0.5;

/// True when `cable` is longer than it should be (see kOverstretch): a drag or a guard has
/// pulled it through a constraint.
bool overstretched(const Cable& cable);

/// Clears the viewport (the free rectangle with `clipToFree`) and draws `world` seen by
/// `camera`, with `overlay` on top.
void drawWorld(const World& world, const Camera& camera, const Overlay& overlay,
               const RenderOptions& options, ImDrawList* text);

/// The colour-bar maximum the renderer uses for `world` and `options` (N).
double tensionScaleFor(const World& world, const RenderOptions& options);

}  // namespace cablelab::ui
