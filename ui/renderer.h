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
#include "ui/overlay_clip.h"
#include "ui/render_options.h"
#include "ui/view_furniture.h"

struct ImDrawList;

namespace cablelab::ui {

/// A rigid cable longer than its rest length by more than this (m) is drawn as overstretched.
inline constexpr double kOverstretch = 0.01;
/// An elastic cable stretched beyond this share of its rest length is drawn as overstretched.
inline constexpr double kOverstretchElastic = 0.5;

/// True when `cable` is longer than it should be (see kOverstretch): a drag or a guard has
/// pulled it through a constraint.
bool overstretched(const Cable& cable);

/// What a drawWorld() call put where on the screen (px, top-left origin): for the sandbox's
/// scripted checks that labels, bars and key never cover each other and the scene fits.
struct DrawnView {
  std::vector<LabelBox> labels;  ///< every label shown
  int hiddenLabels = 0;          ///< labels with no free place (not drawn)
  int labelsOnCables = 0;        ///< labels drawn across a cable's line (no place off them)
  FurnitureLayout furniture;     ///< scale bar, colour bar, key, notes, banner, PAUSED sign
  LabelBox scene;                ///< the moving bodies, pulleys and cables (ui/scene_bounds.h)
  std::vector<ScreenSegment> overlayLines;  ///< drawn arrows, target marks and leader lines (px)
  std::vector<LabelBox> markers;  ///< the overlay's target marks (px), kept clear of labels
};

/// Clears the viewport (the free rectangle with `clipToFree`) and draws `world` seen by
/// `camera`, with `overlay` on top; returns where the labels and screen pieces went.
DrawnView drawWorld(const World& world, const Camera& camera, const Overlay& overlay,
                    const RenderOptions& options, ImDrawList* text);

/// The colour-bar maximum the renderer uses for `world` and `options` (N).
double tensionScaleFor(const World& world, const RenderOptions& options);

}  // namespace cablelab::ui
