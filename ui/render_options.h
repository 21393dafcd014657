// RenderOptions: what the renderer draws and where (ui/renderer.h draws, ui/view_furniture.h
// places the screen-space pieces).
//
// Needs: nothing but the standard library. Plain data, filled by the caller every frame.
#pragma once

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
  /// Presentation mode: the marker key goes as a column top right or a strip along the top,
  /// whichever keeps off the scene's moving parts, and gives way where neither does (out of
  /// it, a key too wide or too long for the view is left out).
  bool keyGivesWay = false;
  /// A large "PAUSED" sign in the view (the sandbox while its simulation is paused).
  bool paused = false;
  /// The colour bar's maximum is one the user locked, not the scene's own: the legend says so.
  bool tensionLocked = false;
};

}  // namespace cablelab::ui
