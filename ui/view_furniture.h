// View furniture: the screen-space pieces drawn over the scene (the scale bar, the tension
// colour bar, the marker key, the overlay's notes, the warning banner and a large PAUSED sign),
// laid out before anything is drawn so that none covers another and the labels keep off them.
//
// Needs: a Dear ImGui frame in progress for text sizes (`text` true), else fixed estimates; GL
// with the renderer's pixel projection for drawing (ui/renderer.cpp calls both).
//
// Places in the free area (px, top-left origin): the scale bar bottom left; the colour bar
// bottom right (narrower when the scale bar would reach it, or stacked above it when even a
// narrow one would not fit); the notes top left; the key top right below `keyTop` (in
// presentation mode, where that would cover the scene, a strip of columns along the top); the
// banner under the notes, left of the key (below it when the room beside it is too narrow); the
// PAUSED sign centred in the bars' row between them (just above them where they leave no room).
#pragma once

#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "ui/camera.h"
#include "ui/label_layout.h"
#include "ui/overlay.h"
#include "ui/render_options.h"

struct ImDrawList;

namespace cablelab::ui {

/// One row of the marker key: which sample to draw, its colour, its text.
struct MarkerKeyRow {
  enum class Sample {
    Anchor,
    WrapPoint,
    PointPulley,
    PulleyInUse,
    PulleyIdle,
    Cross,
    Arrow,
    DashedCross,
    Stretch
  };
  Sample sample;
  Colour colour;
  std::string label;
};

/// Where each piece goes (px); an empty box (x1 <= x0) is not drawn.
struct FurnitureLayout {
  float x = 0, y = 0, w = 0, h = 0;  ///< the free area
  float lineHeight = 13;             ///< of the text font (px)
  LabelBox scaleBar, colourBar, key, notes, banner, paused;
  float barX = 0, barY = 0, barWidth = 0, barHeight = 0, slackWidth = 0;  ///< the colour strip
  float bannerWrap = 0;  ///< the banner's text wrap width (px)
  float pausedSize = 0;  ///< the PAUSED sign's font size (px)
  std::vector<MarkerKeyRow> keyRows;
  float keyRowHeight = 0, keySampleWidth = 0, keyColumnWidth = 0;
  int keyColumns = 1;
  /// Presentation mode (RenderOptions::keyGivesWay): where the key would go as one column top
  /// right and as a strip along the top, and whether the one chosen covers the scene.
  LabelBox keyAsColumn, keyAsStrip;
  bool keyOnScene = false;

  /// The pieces that are drawn, for the labels to keep off.
  std::vector<LabelBox> occupied() const;
};

/// Lays the pieces out for `world` seen by `camera` with `options` (`text`: an ImGui frame is in
/// progress to measure text); `scene` is the scene's moving parts on screen (px), which the key
/// keeps off with `options.keyGivesWay`.
FurnitureLayout layoutFurniture(const World& world, const Overlay& overlay,
                                const RenderOptions& options, const Camera& camera, bool text,
                                const LabelBox& scene = {});

/// Draws them (GL in pixel coordinates, y down; text into `text` when not null); `scale` is the
/// colour bar's maximum (N).
void drawFurniture(const FurnitureLayout& layout, const Overlay& overlay,
                   const RenderOptions& options, double scale, const Camera& camera,
                   ImDrawList* text);

}  // namespace cablelab::ui
