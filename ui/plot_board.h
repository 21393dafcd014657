// The sandbox's plots against time (the Plots section): charts of one or more quantities
// (ui/plot_quantity.h), sampled after every step, the last 30 s kept. A chart shows the last
// `windowSeconds` up to the moment on screen, its vertical range fitted to the data in view (so
// it shrinks back once an outlier has left the view), and exports as a slide-size PNG with axes,
// ticks, units, legend and title, and as CSV (the same samples).
//
// Needs: ui/plot.h (the Plot description; no GL), the engine's World.
#pragma once

#include <array>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "ui/plot.h"
#include "ui/plot_quantity.h"

namespace cablelab::ui {

struct Chart {
  std::vector<Quantity> curves;
  std::vector<std::deque<double>> values;  ///< per curve, one per sample time (NaN: none)
};

class PlotBoard {
 public:
  static constexpr double kKeptSeconds = 30;  ///< samples kept behind the newest
  double windowSeconds = 10;                  ///< time shown (s)
  std::vector<Chart> charts;

  /// Forgets the samples (a reset); `andCharts` the charts too (a new scene).
  void clear(bool andCharts);
  /// Samples every chart's quantities now.
  void record(const World& world, const std::optional<Vec2>& target, int controlledBody);
  /// Adds samples taken at `time` (s): values[chart][curve]. A time at or before the newest
  /// kept one starts a new run there (a rewound world played on): the later samples go.
  void addSample(double time, const std::vector<std::vector<double>>& values);
  /// Adds `q` to chart `chart` (charts.size(): a new chart); earlier samples are NaN. A chart
  /// has one unit on its axis: a quantity in another unit goes to the last chart in its unit,
  /// or a new one. Returns the chart it went to.
  size_t addCurve(size_t chart, const Quantity& q);
  /// Removes a curve (and its chart when it was the last).
  void removeCurve(size_t chart, size_t curve);
  const std::deque<double>& times() const { return times_; }

  /// The time range shown at `now` (s).
  std::array<double, 2> timeRange(double now) const;
  /// The vertical range shown at `now`: the chart's data in timeRange(now), on round numbers.
  std::array<double, 2> valueRange(const Chart& chart, double now) const;
  /// The chart as shown at `now`, as a Plot: title, "time (s)", the quantities' unit, one
  /// series per curve (the samples in view), the ranges above.
  Plot plot(const Chart& chart, const World& world, double now) const;

 private:
  std::deque<double> times_;
};

}  // namespace cablelab::ui
