// The sandbox's plots against time (ui/plot_board.h).
#include "ui/plot_board.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "ui/colormap.h"

namespace cablelab::ui {
namespace {

/// Data in view that varies by less than this share of its size is shown as flat: what is left
/// is the solver's rounding, not motion a slide should show (a body 10 m out wobbling 5 cm, 0.5%,
/// still shows).
constexpr double kNearlyFlat = 1e-3;

/// The word the vertical axis uses for a quantity.
const char* axisWord(Quantity::Kind kind) {
  switch (kind) {
    case Quantity::Kind::X:
    case Quantity::Kind::Y:
      return "position";
    case Quantity::Kind::Vx:
    case Quantity::Kind::Vy:
      return "velocity";
    case Quantity::Kind::Angle:
      return "angle";
    case Quantity::Kind::Length:
      return "length";
    case Quantity::Kind::Tension:
    case Quantity::Kind::SpanTension:
      return "tension";
    case Quantity::Kind::Energy:
      return "energy";
    case Quantity::Kind::ControllerError:
      return "error";
  }
  return "value";
}

}  // namespace

void PlotBoard::clear(bool andCharts) {
  times_.clear();
  if (andCharts) charts.clear();
  for (Chart& c : charts)
    for (auto& v : c.values) v.clear();
}

void PlotBoard::record(const World& world, const std::optional<Vec2>& target, int controlledBody) {
  std::vector<std::vector<double>> values;
  for (const Chart& c : charts) {
    values.emplace_back();
    for (const Quantity& q : c.curves)
      values.back().push_back(quantityValue(world, target, controlledBody, q));
  }
  addSample(world.time(), values);
}

void PlotBoard::addSample(double time, const std::vector<std::vector<double>>& values) {
  auto popBack = [&] {
    times_.pop_back();
    for (Chart& c : charts)
      for (auto& v : c.values) v.pop_back();
  };
  auto popFront = [&] {
    times_.pop_front();
    for (Chart& c : charts)
      for (auto& v : c.values) v.pop_front();
  };
  while (!times_.empty() && times_.back() >= time) popBack();
  times_.push_back(time);
  for (size_t i = 0; i < charts.size(); ++i)
    for (size_t k = 0; k < charts[i].values.size(); ++k)
      charts[i].values[k].push_back(i < values.size() && k < values[i].size()
                                        ? values[i][k]
                                        : std::numeric_limits<double>::quiet_NaN());
  while (times_.size() > 1 && time - times_.front() > kKeptSeconds + 1e-9) popFront();
}

size_t PlotBoard::addCurve(size_t chart, const Quantity& q) {
  // Newtons and metres on one axis ("value (N, m)") read as neither: one unit per chart.
  const std::string unit = quantityUnit(q.kind);
  auto sameUnit = [&](const Chart& c) {
    return c.curves.empty() || quantityUnit(c.curves[0].kind) == unit;
  };
  if (chart < charts.size() && !sameUnit(charts[chart])) {
    chart = charts.size();
    for (size_t i = charts.size(); i-- > 0;)
      if (sameUnit(charts[i])) {
        chart = i;
        break;
      }
  }
  if (chart >= charts.size()) {
    charts.emplace_back();
    chart = charts.size() - 1;
  }
  Chart& c = charts[chart];
  if (std::find(c.curves.begin(), c.curves.end(), q) != c.curves.end()) return chart;
  c.curves.push_back(q);
  c.values.emplace_back(times_.size(), std::numeric_limits<double>::quiet_NaN());
  return chart;
}

void PlotBoard::removeCurve(size_t chart, size_t curve) {
  if (chart >= charts.size() || curve >= charts[chart].curves.size()) return;
  Chart& c = charts[chart];
  c.curves.erase(c.curves.begin() + static_cast<long>(curve));
  c.values.erase(c.values.begin() + static_cast<long>(curve));
  if (c.curves.empty()) charts.erase(charts.begin() + static_cast<long>(chart));
}

std::array<double, 2> PlotBoard::timeRange(double now) const {
  // A run younger than the window fills it from the left.
  const double start = times_.empty() ? 0 : times_.front();
  const double lo = std::max(now - windowSeconds, std::min(start, now));
  return {lo, lo + windowSeconds};
}

std::array<double, 2> PlotBoard::valueRange(const Chart& chart, double now) const {
  const auto [t0, t1] = timeRange(now);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t i = 0; i < times_.size(); ++i) {
    if (times_[i] < t0 - 1e-9 || times_[i] > std::min(t1, now) + 1e-9) continue;
    for (const auto& v : chart.values)
      if (std::isfinite(v[i])) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
  }
  if (!(hi >= lo)) return {0, 1};
  // Flat, or nearly (a rope's steady tension wobbling in its sixth digit): a band of 5% about
  // the value, so that the curve is a level line between distinct ticks rather than a cliff
  // between eight ticks that all read "13.08".
  const double size = std::max(std::abs(lo), std::abs(hi));
  if (hi - lo < std::max(kNearlyFlat * size, 1e-9)) {
    const double middle = 0.5 * (lo + hi), half = std::max(0.05 * size, 1e-6);
    lo = middle - half, hi = middle + half;
  }
  // Padded 5% (the curve clear of the frame), rounded outwards to the plot's tick step (an
  // eighth of the span, 1, 2 or 5 times a power of 10).
  const double pad = 0.05 * (hi - lo);
  lo -= pad, hi += pad;
  const double step = niceCeil((hi - lo) / 8);
  return {std::floor(lo / step) * step, std::ceil(hi / step) * step};
}

Plot PlotBoard::plot(const Chart& chart, const World& world, double now) const {
  Plot p;
  std::set<std::string> words, units;
  std::string names;
  for (const Quantity& q : chart.curves) {
    words.insert(axisWord(q.kind));
    units.insert(quantityUnit(q.kind));
  }
  std::string unit;
  for (const std::string& u : units) unit += (unit.empty() ? "" : ", ") + u;
  p.yLabel = (words.size() == 1 ? *words.begin() : std::string("value")) + " (" + unit + ")";
  p.xLabel = "time (s)";
  const std::string scene = world.scene().name.empty() ? "scene" : world.scene().name;
  p.title = scene + ": " +
            (chart.curves.size() == 1 ? quantityName(world, chart.curves[0])
                                      : (words.size() == 1 ? *words.begin() : "values")) +
            " against time";
  const auto range = timeRange(now);
  p.xRange = range;
  p.yRange = valueRange(chart, now);
  for (size_t k = 0; k < chart.curves.size(); ++k) {
    std::vector<double> x, y;
    for (size_t i = 0; i < times_.size(); ++i)
      if (times_[i] >= range[0] - 1e-9 && times_[i] <= now + 1e-9)
        x.push_back(times_[i]), y.push_back(chart.values[k][i]);
    p.addLine(
        quantityName(world, chart.curves[k]) + " (" + quantityUnit(chart.curves[k].kind) + ")",
        std::move(x), std::move(y));
    // Earlier curves drawn wider: one that coincides with a later one still shows at its edges.
    const double later = static_cast<double>(chart.curves.size() - 1 - k);
    p.series.back().lineWidth = static_cast<float>(2 + 1.5 * std::min(later, 3.0));
  }
  return p;
}

}  // namespace cablelab::ui
