// Plots to PNG: line plots, scatter plots (with an optional y = x line) and quiver plots,
// with axes, ticks, labels, a title and a legend. Rendered offscreen like the snapshots.
//
// Needs: cablelab_offscreen (OSMesa + Dear ImGui + libpng); no display. Link that library
// (the `cablelab` CLI already does) and include this header. Example, a measured-vs-predicted
// scatter plot and a force quiver plot:
//
//   cablelab::ui::Plot scatter("Vertical force", "measured fy (N)", "model fy (N)");
//   scatter.identityLine = true;
//   scatter.addScatter("samples", measured, predicted);
//   cablelab::ui::writePlotPng(scatter, "out/fy.png");
//
//   cablelab::ui::Plot quiver("Force field", "x (m)", "y (m)");
//   quiver.equalAspect = true;
//   quiver.addArrows("measured", x, y, fx, fy);
//   quiver.addArrows("model", x, y, gx, gy);  // same auto scale: arrows are comparable
//   cablelab::ui::writePlotPng(quiver, "out/quiver.png", 800, 800);
//
// Non-finite values are skipped. Axis ranges come from the data (padded 5%) unless given.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ui/image.h"
#include "ui/overlay.h"

namespace cablelab::ui {

struct PlotSeries {
  enum class Style { Line, Markers, LineAndMarkers, Dashed };  ///< Dashed: a dashed line
  std::string label;         ///< legend text; empty = not in the legend
  std::vector<double> x, y;  ///< same length
  Style style = Style::Line;
  std::optional<Colour> colour;  ///< default: the next palette colour
  float markerRadius = 3.0f;     ///< px
  float lineWidth = 2.0f;        ///< px
};

/// Arrows from (x, y) to (x + s u, y + s v), s the plot's common arrow scale.
struct PlotArrows {
  std::string label;
  std::vector<double> x, y, u, v;  ///< same length
  std::optional<Colour> colour;
  float lineWidth = 1.5f;  ///< px
};

/// Text at a data point (its left edge at x, vertically centred on y), e.g. naming a marker.
struct PlotLabel {
  double x = 0, y = 0;
  std::string text;
};

struct Plot {
  Plot() = default;
  Plot(std::string title, std::string xLabel, std::string yLabel)
      : title(std::move(title)), xLabel(std::move(xLabel)), yLabel(std::move(yLabel)) {}

  std::string title, xLabel, yLabel;
  std::vector<PlotSeries> series;
  std::vector<PlotArrows> arrows;
  bool identityLine = false;  ///< draw y = x (dashed) and use the same range on both axes
  std::string identityLabel;  ///< legend text of the y = x line; empty = not in the legend
  std::vector<PlotLabel> labels;
  bool equalAspect = false;  ///< one data unit is as many pixels on x as on y
  /// Data units per unit of u, v for every arrow set; <= 0: the longest arrow is 8% of the
  /// larger axis range.
  double arrowScale = 0;
  std::optional<std::array<double, 2>> xRange, yRange;  ///< fixed {min, max}

  Plot& addLine(std::string label, std::vector<double> x, std::vector<double> y);
  Plot& addScatter(std::string label, std::vector<double> x, std::vector<double> y);
  Plot& addArrows(std::string label, std::vector<double> x, std::vector<double> y,
                  std::vector<double> u, std::vector<double> v);
};

/// Renders `plot` into a width x height image. Throws std::runtime_error (mismatched series
/// lengths, bad size, no OSMesa).
Image renderPlot(const Plot& plot, int width = 800, int height = 600);

/// renderPlot() then writePng(); throws std::runtime_error naming `path` on failure.
void writePlotPng(const Plot& plot, const std::string& path, int width = 800, int height = 600);

}  // namespace cablelab::ui
