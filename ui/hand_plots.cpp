#include "ui/hand_plots.h"

#include <cmath>

#include "ui/image.h"
#include "ui/plot_image.h"

namespace cablelab::ui {
namespace hand_plots {  // named: unity batches join .cpp files

// The panel's colours (ui/controller_panel.cpp, handPanel).
const Colour kTop = {200 / 255.0f, 60 / 255.0f, 30 / 255.0f, 1};
const Colour kBottom = {40 / 255.0f, 90 / 255.0f, 200 / 255.0f, 1};
const Colour kError = {170 / 255.0f, 20 / 255.0f, 120 / 255.0f, 1};
const Colour kX = {200 / 255.0f, 90 / 255.0f, 0, 1};
const Colour kY = {0, 130 / 255.0f, 90 / 255.0f, 1};

/// Series `index` of the history against time (the samples with a value).
PlotSeries handSeries(const TimeHistory& h, int index, const std::string& label,
                      const Colour& colour, bool dashed) {
  PlotSeries s;
  s.label = label;
  s.colour = colour;
  s.style = dashed ? PlotSeries::Style::Dashed : PlotSeries::Style::Line;
  for (int k = 0; k < h.count; ++k) {
    const int i = h.slot(k);
    const float v = h.values[index][i];
    if (!std::isfinite(v)) continue;
    s.x.push_back(h.t[i]);
    s.y.push_back(v);
  }
  return s;
}

}  // namespace hand_plots

std::vector<Plot> handPlots(const HandControlState& h, double tensionTop) {
  using namespace hand_plots;
  const TimeHistory& t = h.history;
  Plot tensions("hand: membrane tensions", "time (s)", "tension (N)");
  tensions.series = {handSeries(t, 0, "top membrane", kTop, false),
                     handSeries(t, 1, "bottom membrane", kBottom, true)};
  tensions.series[0].lineWidth = 4;  // under the dashed bottom one
  tensions.yRange = std::array<double, 2>{0, tensionTop};
  Plot error("hand: distance from the box to the target", "time (s)", "|box - target| (m)");
  error.series = {handSeries(t, 2, "|box - target|", kError, false)};
  Plot position("hand: box position and target", "time (s)", "position (m)");
  position.series = {handSeries(t, 3, "box x", kX, false), handSeries(t, 4, "box y", kY, false),
                     handSeries(t, 5, "target x", kX, true),
                     handSeries(t, 6, "target y", kY, true)};
  return {tensions, error, position};
}

std::vector<std::string> exportHandPlots(const HandControlState& h, double tensionTop,
                                         const std::string& stem, int width, int height) {
  static const char* kNames[] = {"tensions", "error", "position"};
  const std::vector<Plot> plots = handPlots(h, tensionTop);
  std::vector<std::string> paths;
  for (size_t k = 0; k < plots.size(); ++k) {
    paths.push_back(stem + "-" + kNames[k] + ".png");
    writePng(renderPlotImage(plots[k], width, height), paths.back());
  }
  return paths;
}

}  // namespace cablelab::ui
