// A Plot (ui/plot.h) at slide size without GL: drawn by plot_draw.h into a Dear ImGui context of
// its own (the default font rasterized at the plot's scale) and rasterized on the CPU
// (draw_raster.h). The sandbox window exports its plots with it (it links libGL, where the
// OSMesa renderer of plot.h cannot run; README.md). Also the plot's data as CSV.
//
// Needs: Dear ImGui and libpng only (cablelab_render). Safe to call inside another ImGui frame:
// the caller's context is restored.
#pragma once

#include <string>

#include "ui/image.h"
#include "ui/plot.h"

namespace cablelab::ui {

/// How much renderPlotImage() grows renderPlot()'s lengths (text, lines, margins) at width x
/// height: min(width / 640, height / 400), so that text on a slide is about 1/30 of its height.
float slideScale(int width, int height);

/// `plot` as a width x height image, every length slideScale() times renderPlot()'s. Throws
/// std::runtime_error as checkPlot().
Image renderPlotImage(const Plot& plot, int width = 1920, int height = 1080);

/// The series of `plot` that share one x column, as CSV: a header `xLabel,label 1,label 2,...`
/// and one row per x, numbers in full precision (%.17g; non-finite: empty). Series of another
/// length than the first are an error. Throws std::runtime_error naming `path`.
void writePlotCsv(const Plot& plot, const std::string& path);

}  // namespace cablelab::ui
