#include "ui/plot_draw.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "ui/colormap.h"
#include "ui/palette.h"

namespace cablelab::ui {
namespace {

constexpr Colour kPalette[] = {{0.12f, 0.47f, 0.71f, 1}, {1.0f, 0.50f, 0.05f, 1},
                               {0.17f, 0.63f, 0.17f, 1}, {0.84f, 0.15f, 0.16f, 1},
                               {0.58f, 0.40f, 0.74f, 1}, {0.55f, 0.34f, 0.29f, 1}};
const ImU32 kInk = IM_COL32(30, 30, 30, 255);
const ImU32 kGrid = IM_COL32(225, 225, 225, 255);

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  bool empty() const { return !(hi >= lo); }
  double span() const { return hi - lo; }
  void settle() {
    if (empty()) lo = 0, hi = 1;
    if (span() <= 0)
      lo -= 0.5 * std::max(1.0, std::abs(lo)), hi += 0.5 * std::max(1.0, std::abs(hi));
  }
  void pad(double fraction) {
    const double p = fraction * span();
    lo -= p, hi += p;
  }
  void grow(double newSpan) {
    const double c = 0.5 * (lo + hi);
    lo = c - 0.5 * newSpan, hi = c + 0.5 * newSpan;
  }
};

std::string tickText(double v, double step) {
  if (std::abs(v) < 1e-9 * step) v = 0;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

void checkLengths(const std::string& what, size_t n, std::initializer_list<size_t> others) {
  for (size_t m : others)
    if (m != n) throw std::runtime_error("plot: " + what + ": coordinate arrays differ in length");
}

void arrowHead(ImDrawList* draw, ImVec2 from, ImVec2 to, ImU32 colour, float u = 1) {
  const float dx = to.x - from.x, dy = to.y - from.y;
  const float length = std::sqrt(dx * dx + dy * dy);
  if (length < 1.0f) return;
  const float ux = dx / length, uy = dy / length, head = std::min(7.0f * u, 0.45f * length);
  const ImVec2 base(to.x - head * ux, to.y - head * uy);
  draw->AddTriangleFilled(to, ImVec2(base.x - 0.45f * head * uy, base.y + 0.45f * head * ux),
                          ImVec2(base.x + 0.45f * head * uy, base.y - 0.45f * head * ux), colour);
}

/// Median distance from each arrow site to its nearest other site (0 with fewer than 2 sites).
double medianSpacing(const std::vector<PlotArrows>& sets) {
  std::vector<std::pair<double, double>> sites;
  for (const auto& a : sets)
    for (size_t i = 0; i < a.x.size() && sites.size() < 2000; ++i)
      if (std::isfinite(a.x[i]) && std::isfinite(a.y[i])) sites.emplace_back(a.x[i], a.y[i]);
  std::vector<double> nearest;
  for (size_t i = 0; i < sites.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < sites.size(); ++j) {
      const double d =
          std::hypot(sites[i].first - sites[j].first, sites[i].second - sites[j].second);
      if (d > 0) best = std::min(best, d);
    }
    if (std::isfinite(best)) nearest.push_back(best);
  }
  if (nearest.empty()) return 0;
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return nearest[nearest.size() / 2];
}

void checkSize(const Plot& plot, int width, int height, float u) {
  const float top = (plot.title.empty() ? 24 : 44) * u;
  if (width - 96 * u < 20 || height - 52 * u - top < 20)
    throw std::runtime_error("plot: image too small");
}

}  // namespace

Plot& Plot::addLine(std::string label, std::vector<double> x, std::vector<double> y) {
  series.push_back({std::move(label), std::move(x), std::move(y), PlotSeries::Style::Line, {}});
  return *this;
}

Plot& Plot::addScatter(std::string label, std::vector<double> x, std::vector<double> y) {
  series.push_back({std::move(label), std::move(x), std::move(y), PlotSeries::Style::Markers, {}});
  return *this;
}

Plot& Plot::addArrows(std::string label, std::vector<double> x, std::vector<double> y,
                      std::vector<double> u, std::vector<double> v) {
  arrows.push_back({std::move(label), std::move(x), std::move(y), std::move(u), std::move(v), {}});
  return *this;
}

Colour plotColour(int index) {
  return kPalette[index % 6];
}

void checkPlot(const Plot& plot, int width, int height) {
  for (const auto& s : plot.series) checkLengths(s.label, s.x.size(), {s.y.size()});
  for (const auto& a : plot.arrows)
    checkLengths(a.label, a.x.size(), {a.y.size(), a.u.size(), a.v.size()});
  checkSize(plot, width, height, 1);
}

void drawPlot(ImDrawList* draw, const Plot& plot, int width, int height, float scale,
              ImVec2 origin) {
  checkPlot(plot, width, height);
  const float u = scale;  // px per unit-scale pixel
  checkSize(plot, width, height, u);

  // Data ranges, then the common arrow scale, then the arrow tips.
  Range rx, ry;
  for (const auto& s : plot.series)
    for (size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) rx.add(s.x[i]), ry.add(s.y[i]);
  double longest = 0;
  for (const auto& a : plot.arrows)
    for (size_t i = 0; i < a.x.size(); ++i) {
      rx.add(a.x[i]), ry.add(a.y[i]);
      const double l = std::hypot(a.u[i], a.v[i]);
      if (std::isfinite(l)) longest = std::max(longest, l);
    }
  Range base = rx;
  base.settle();
  Range baseY = ry;
  baseY.settle();
  // Default: the longest arrow spans 90% of the median nearest-neighbour distance between
  // sites (so neighbours do not overlap), but at least 5% of the larger axis range.
  const double larger = std::max(base.span(), baseY.span());
  const double arrowScale =
      plot.arrowScale > 0 ? plot.arrowScale
      : longest > 0       ? std::max(0.9 * medianSpacing(plot.arrows), 0.05 * larger) / longest
                          : 0;
  for (const auto& a : plot.arrows)
    for (size_t i = 0; i < a.x.size(); ++i)
      if (std::isfinite(a.u[i]) && std::isfinite(a.v[i]))
        rx.add(a.x[i] + arrowScale * a.u[i]), ry.add(a.y[i] + arrowScale * a.v[i]);
  if (plot.identityLine && !rx.empty() && !ry.empty()) {
    rx.add(ry.lo), rx.add(ry.hi);
    ry = rx;
  }
  rx.settle(), ry.settle();
  rx.pad(0.05), ry.pad(0.05);
  if (plot.xRange) rx.lo = (*plot.xRange)[0], rx.hi = (*plot.xRange)[1], rx.settle();
  if (plot.yRange) ry.lo = (*plot.yRange)[0], ry.hi = (*plot.yRange)[1], ry.settle();

  // Plot area in pixels (y down).
  const float left = origin.x + 72 * u, right = origin.x + static_cast<float>(width) - 24 * u;
  const float top = origin.y + (plot.title.empty() ? 24 : 44) * u;
  const float bottom = origin.y + static_cast<float>(height) - 52 * u;
  if (plot.equalAspect) {
    const double sx = rx.span() / (right - left), sy = ry.span() / (bottom - top);
    if (sx > sy)
      ry.grow(sx * (bottom - top));
    else
      rx.grow(sy * (right - left));
  }
  auto map = [&](double x, double y) {
    return ImVec2(static_cast<float>(left + (x - rx.lo) / rx.span() * (right - left)),
                  static_cast<float>(bottom - (y - ry.lo) / ry.span() * (bottom - top)));
  };

  {
    // Grid, ticks and tick labels.
    const double xStep = niceCeil(rx.span() / 8), yStep = niceCeil(ry.span() / 8);
    for (double t = std::ceil(rx.lo / xStep) * xStep; t <= rx.hi + 1e-9 * xStep; t += xStep) {
      const float x = map(t, ry.lo).x;
      draw->AddLine(ImVec2(x, top), ImVec2(x, bottom), kGrid, u);
      draw->AddLine(ImVec2(x, bottom), ImVec2(x, bottom + 5 * u), kInk, u);
      const std::string s = tickText(t, xStep);
      draw->AddText(ImVec2(x - 3.5f * u * s.size(), bottom + 8 * u), kInk, s.c_str());
    }
    for (double t = std::ceil(ry.lo / yStep) * yStep; t <= ry.hi + 1e-9 * yStep; t += yStep) {
      const float y = map(rx.lo, t).y;
      draw->AddLine(ImVec2(left, y), ImVec2(right, y), kGrid, u);
      draw->AddLine(ImVec2(left - 5 * u, y), ImVec2(left, y), kInk, u);
      const std::string s = tickText(t, yStep);
      draw->AddText(ImVec2(left - (9 + 7.0f * s.size()) * u, y - 7 * u), kInk, s.c_str());
    }
    draw->AddRect(ImVec2(left, top), ImVec2(right, bottom), kInk, 0, 0, u);

    // Data, clipped to the plot area.
    draw->PushClipRect(ImVec2(left, top), ImVec2(right, bottom), true);
    if (plot.identityLine) {
      const double lo = std::max(rx.lo, ry.lo), hi = std::min(rx.hi, ry.hi);
      const int dashes = 40;
      for (int k = 0; k < dashes; k += 2)
        draw->AddLine(map(lo + (hi - lo) * k / dashes, lo + (hi - lo) * k / dashes),
                      map(lo + (hi - lo) * (k + 1) / dashes, lo + (hi - lo) * (k + 1) / dashes),
                      IM_COL32(120, 120, 120, 255), 1.5f * u);
    }
    std::vector<std::pair<std::string, std::pair<ImU32, int>>> legend;  // label, colour, kind
    if (plot.identityLine && !plot.identityLabel.empty())
      legend.push_back({plot.identityLabel, {IM_COL32(120, 120, 120, 255), 4}});
    int next = 0;
    for (const auto& s : plot.series) {
      const ImU32 c = toImU32(s.colour.value_or(kPalette[next++ % 6]));
      const bool lines = s.style != PlotSeries::Style::Markers;
      const bool markers =
          s.style == PlotSeries::Style::Markers || s.style == PlotSeries::Style::LineAndMarkers;
      const bool dashed = s.style == PlotSeries::Style::Dashed;
      std::vector<ImVec2> run;
      auto flush = [&] {
        if (run.size() >= 2 && !dashed)
          draw->AddPolyline(run.data(), static_cast<int>(run.size()), c, 0, s.lineWidth * u);
        if (run.size() >= 2 && dashed) {
          // 9 px on, 6 px off, measured along the polyline.
          const float kOn = 9 * u, kPeriod = 15 * u;
          float along = 0;
          for (size_t i = 0; i + 1 < run.size(); ++i) {
            const ImVec2 a = run[i], b = run[i + 1];
            const float len = std::hypot(b.x - a.x, b.y - a.y);
            float t = 0;
            while (t < len) {
              const float phase = std::fmod(along + t, kPeriod);
              const float step = std::min(len - t, phase < kOn ? kOn - phase : kPeriod - phase);
              if (phase < kOn && len > 0)
                draw->AddLine(ImVec2(a.x + (b.x - a.x) * t / len, a.y + (b.y - a.y) * t / len),
                              ImVec2(a.x + (b.x - a.x) * (t + step) / len,
                                     a.y + (b.y - a.y) * (t + step) / len),
                              c, s.lineWidth * u);
              t += std::max(step, 1e-3f);
            }
            along += len;
          }
        }
        run.clear();
      };
      for (size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
          flush();
          continue;
        }
        const ImVec2 p = map(s.x[i], s.y[i]);
        if (lines) run.push_back(p);
        if (markers) draw->AddCircleFilled(p, s.markerRadius * u, c, 16);
      }
      flush();
      if (!s.label.empty())
        legend.push_back({s.label, {c, dashed ? 4 : markers ? (lines ? 2 : 1) : 0}});
    }
    for (const auto& a : plot.arrows) {
      const ImU32 c = toImU32(a.colour.value_or(kPalette[next++ % 6]));
      for (size_t i = 0; i < a.x.size(); ++i) {
        const double ex = a.x[i] + arrowScale * a.u[i], ey = a.y[i] + arrowScale * a.v[i];
        if (!std::isfinite(a.x[i]) || !std::isfinite(a.y[i]) || !std::isfinite(ex) ||
            !std::isfinite(ey))
          continue;
        const ImVec2 from = map(a.x[i], a.y[i]), to = map(ex, ey);
        draw->AddLine(from, to, c, a.lineWidth * u);
        arrowHead(draw, from, to, c, u);
      }
      if (!a.label.empty()) legend.push_back({a.label, {c, 3}});
    }
    for (const PlotLabel& l : plot.labels)
      if (std::isfinite(l.x) && std::isfinite(l.y)) {
        const ImVec2 p = map(l.x, l.y);
        draw->AddText(ImVec2(p.x, p.y - 7 * u), kInk, l.text.c_str());
      }
    draw->PopClipRect();

    // Title, axis labels, legend.
    if (!plot.title.empty())
      draw->AddText(ImVec2(0.5f * (left + right) - 3.5f * u * plot.title.size(), origin.y + 16 * u),
                    kInk, plot.title.c_str());
    if (!plot.xLabel.empty())
      draw->AddText(ImVec2(0.5f * (left + right) - 3.5f * u * plot.xLabel.size(), bottom + 28 * u),
                    kInk, plot.xLabel.c_str());
    if (!plot.yLabel.empty())
      draw->AddText(ImVec2(origin.x + 8 * u, top - 18 * u), kInk, plot.yLabel.c_str());
    if (!legend.empty()) {
      size_t longestLabel = 0;
      for (const auto& l : legend) longestLabel = std::max(longestLabel, l.first.size());
      const float w = (40 + 7.0f * longestLabel) * u, h = (8 + 16.0f * legend.size()) * u;
      // The corner of the plot area that covers the fewest data points.
      std::vector<ImVec2> points;
      for (const auto& series : plot.series)
        for (size_t i = 0; i < series.x.size(); ++i)
          points.push_back(map(series.x[i], series.y[i]));
      for (const auto& a : plot.arrows)
        for (size_t i = 0; i < a.x.size(); ++i) {
          points.push_back(map(a.x[i], a.y[i]));
          points.push_back(map(a.x[i] + arrowScale * a.u[i], a.y[i] + arrowScale * a.v[i]));
        }
      const float m = 8 * u;
      const ImVec2 corners[4] = {ImVec2(right - w - m, top + m), ImVec2(left + m, top + m),
                                 ImVec2(right - w - m, bottom - h - m),
                                 ImVec2(left + m, bottom - h - m)};
      ImVec2 p0 = corners[0];
      long fewest = -1;
      for (const ImVec2& c : corners) {
        long covered = 0;
        for (const ImVec2& q : points)
          covered += q.x >= c.x - 4 * u && q.x <= c.x + w + 4 * u && q.y >= c.y - 4 * u &&
                     q.y <= c.y + h + 4 * u;
        if (fewest < 0 || covered < fewest) fewest = covered, p0 = c;
      }
      draw->AddRectFilled(p0, ImVec2(p0.x + w, p0.y + h), IM_COL32(255, 255, 255, 230));
      draw->AddRect(p0, ImVec2(p0.x + w, p0.y + h), IM_COL32(160, 160, 160, 255), 0, 0, u);
      for (size_t i = 0; i < legend.size(); ++i) {
        const float y = p0.y + (12 + 16.0f * i) * u;
        const auto [c, kind] = legend[i].second;
        if (kind == 0 || kind == 2)
          draw->AddLine(ImVec2(p0.x + 6 * u, y), ImVec2(p0.x + 28 * u, y), c, 2.0f * u);
        if (kind == 1 || kind == 2)
          draw->AddCircleFilled(ImVec2(p0.x + 17 * u, y), 3.0f * u, c, 12);
        if (kind == 4)
          for (float x = 6; x < 28; x += 8)
            draw->AddLine(ImVec2(p0.x + x * u, y), ImVec2(p0.x + std::min(x + 5, 28.0f) * u, y), c,
                          2.0f * u);
        if (kind == 3) {
          draw->AddLine(ImVec2(p0.x + 6 * u, y), ImVec2(p0.x + 28 * u, y), c, 1.5f * u);
          arrowHead(draw, ImVec2(p0.x + 6 * u, y), ImVec2(p0.x + 28 * u, y), c, u);
        }
        draw->AddText(ImVec2(p0.x + 34 * u, y - 7 * u), kInk, legend[i].first.c_str());
      }
    }
  }
}

}  // namespace cablelab::ui
