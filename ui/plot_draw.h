// The drawing of a Plot (ui/plot.h) as Dear ImGui draw commands, with no GL (here too: Plot's
// own methods): the offscreen renderer (plot.cpp, OSMesa) and the window's slide export
// (plot_image.h, on the CPU) both draw plots with it.
//
// Needs: Dear ImGui with a frame in progress (a draw list and a font).
#pragma once

#include "ui/plot.h"

#include <imgui.h>

namespace cablelab::ui {

/// The colour of a plot's `index`-th series without a colour of its own.
Colour plotColour(int index);

/// Throws std::runtime_error if the series' lengths differ or width x height is too small.
void checkPlot(const Plot& plot, int width, int height);

/// Draws `plot` over the width x height area at `origin` (px) onto a white background (not
/// drawn), every length in pixels times `scale`; text in the current font (sized 13 x scale px
/// for the layout to fit). Throws as checkPlot().
void drawPlot(ImDrawList* draw, const Plot& plot, int width, int height, float scale = 1,
              ImVec2 origin = ImVec2(0, 0));

}  // namespace cablelab::ui
