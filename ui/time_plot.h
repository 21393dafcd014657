// Live time plots of the sandbox's panels: a fixed-length history of samples against time, and
// a plot of several of its series in one frame with a legend, drawn with Dear ImGui.
#pragma once

#include <imgui.h>

#include <initializer_list>
#include <vector>

#include "ui/sandbox.h"

namespace cablelab::ui {

/// Fixed-length history of samples against time (oldest overwritten), for the live plots.
struct TimeHistory {
  static constexpr int kLength = 900;      ///< samples (15 s at the default 60 Hz)
  std::vector<float> t;                    ///< s
  std::vector<std::vector<float>> values;  ///< one ring per series, NaN = no value
  int head = 0, count = 0;
  explicit TimeHistory(int series = 0);
  void push(float time, const std::vector<float>& sample);
  void clear();
  /// The slot of the k-th oldest sample kept (0 <= k < count).
  int slot(int k) const { return (head - count + k + 2 * kLength) % kLength; }
};

/// A dashed line: a dash of kDashLength every kDashPeriod (px).
constexpr float kDashPeriod = 10, kDashLength = 6;

/// One series of a TimeHistory drawn in a time plot.
struct PlotLine {
  const char* label;
  int series;
  ImU32 colour;
  bool dashed = false;  ///< targets are dashed
  /// Where the dashes start (px along the line): a dashed line over another dashed line at an
  /// offset of half a period fills its gaps, so both colours show where the two are equal.
  float dashPhase = 0;
};

/// The plot range for the plotted series: `smallest`, grown to a nice number holding every
/// |value| in the history (15 s), so that it shrinks back once a far target has left the plot.
float fittedRange(const TimeHistory& h, std::initializer_list<PlotLine> lines, float smallest);

/// Series of `h` against time over [lo, hi] (a fixed range from the caller: the plot does not
/// jump as samples come and go), with a legend above (`labels`: its texts' rectangles).
void timePlot(const char* id, const TimeHistory& h, std::initializer_list<PlotLine> lines,
              const char* unit, float height, float lo, float hi,
              std::vector<PanelRect>* labels = nullptr);

}  // namespace cablelab::ui
