// Live time plots (time_plot.h).
#include "ui/time_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/colormap.h"

namespace cablelab::ui {

TimeHistory::TimeHistory(int series)
    : t(kLength, 0.0f), values(series, std::vector<float>(kLength, 0.0f)) {}

void TimeHistory::push(float time, const std::vector<float>& sample) {
  t[head] = time;
  for (size_t s = 0; s < values.size() && s < sample.size(); ++s) values[s][head] = sample[s];
  head = (head + 1) % kLength;
  count = std::min(count + 1, kLength);
}

void TimeHistory::clear() {
  head = count = 0;
}

float fittedRange(const TimeHistory& h, std::initializer_list<PlotLine> lines, float smallest) {
  float range = smallest;
  for (const PlotLine& l : lines)
    for (int k = 0; k < h.count; ++k) {
      const float v = std::abs(h.values[l.series][k]);
      if (std::isfinite(v) && v > range) range = static_cast<float>(niceCeil(v));
    }
  return range;
}

namespace {

void dashedPolyline(ImDrawList* draw, const std::vector<ImVec2>& run, ImU32 colour, float phase) {
  for (size_t k = 1; k < run.size(); ++k) {
    const ImVec2 a = run[k - 1], b = run[k];
    const float len = std::hypot(b.x - a.x, b.y - a.y);
    if (len <= 0) continue;
    for (float s = -std::fmod(phase, kDashPeriod); s < len; s += kDashPeriod) {
      const float s0 = std::max(s, 0.0f), s1 = std::min(s + kDashLength, len);
      if (s1 > s0)
        draw->AddLine(ImVec2(a.x + (b.x - a.x) * s0 / len, a.y + (b.y - a.y) * s0 / len),
                      ImVec2(a.x + (b.x - a.x) * s1 / len, a.y + (b.y - a.y) * s1 / len), colour,
                      1.5f);
    }
    phase += len;
  }
}

/// The legend of a time plot: the range, then each line's label in its colour, left to right
/// a text gap apart, on as many rows as the plot's width needs (at twice the text size the
/// labels ran into each other). Returns the rows used; `labels` gets each text's rectangle.
int timePlotLegend(ImDrawList* draw, const ImVec2& p0, float width, const char* range,
                   std::initializer_list<PlotLine> lines, std::vector<PanelRect>* labels) {
  const float lh = ImGui::GetTextLineHeight(), gap = 0.6f * lh, left = p0.x + 4;
  float x = left, y = p0.y + 1;
  int rows = 1;
  auto place = [&](const char* text, ImU32 colour) {
    const ImVec2 size = ImGui::CalcTextSize(text);
    if (x > left && x + size.x > p0.x + width - 4) x = left, y += lh, ++rows;
    draw->AddText(ImVec2(x, y), colour, text);
    if (labels) labels->push_back({x, y, size.x, size.y});
    x += size.x + gap;
  };
  place(range, IM_COL32(90, 90, 90, 255));
  for (const PlotLine& l : lines) place(l.label, l.colour);
  return rows;
}

}  // namespace

void timePlot(const char* id, const TimeHistory& h, std::initializer_list<PlotLine> lines,
              const char* unit, float height, float lo, float hi, std::vector<PanelRect>* labels) {
  const float width = ImGui::GetContentRegionAvail().x;
  const float lh = ImGui::GetTextLineHeight();
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton(id, ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p1(p0.x + width, p0.y + height);
  draw->AddRectFilled(p0, p1, IM_COL32(250, 250, 250, 255));
  draw->AddRect(p0, p1, IM_COL32(150, 150, 150, 255));
  if (h.count < 2) {
    draw->AddText(ImVec2(p0.x + 6, p0.y + 4), IM_COL32(120, 120, 120, 255), "no samples yet");
    return;
  }
  auto at = [&](int k) { return h.slot(k); };
  const float t0 = h.t[at(0)], t1 = std::max(h.t[at(h.count - 1)], t0 + 1e-3f);
  hi = std::max(hi, lo + 1e-6f);
  char text[96];
  std::snprintf(text, sizeof text, "%g .. %g %s", lo, hi, unit);
  const int rows = timePlotLegend(draw, p0, width, text, lines, labels);
  const float left = p0.x + 4, right = p1.x - 4, top = p0.y + rows * lh + 3, bottom = p1.y - lh - 1;
  auto map = [&](float t, float v) {
    return ImVec2(left + (t - t0) / (t1 - t0) * (right - left),
                  bottom - (v - lo) / (hi - lo) * (bottom - top));
  };
  const float zero = map(t0, std::clamp(0.0f, lo, hi)).y;
  draw->AddLine(ImVec2(left, zero), ImVec2(right, zero), IM_COL32(190, 190, 190, 255));
  std::vector<ImVec2> run;
  auto flush = [&](const PlotLine& l) {
    if (run.size() >= 2) {
      if (l.dashed)
        dashedPolyline(draw, run, l.colour, l.dashPhase);
      else
        draw->AddPolyline(run.data(), static_cast<int>(run.size()), l.colour, 0, 1.5f);
    }
    run.clear();
  };
  // At most the lowest and the highest sample of each pixel column, in time order: the same
  // picture as every sample with a fraction of the vertices (900 samples over ~250 px).
  for (const PlotLine& l : lines) {
    int column = -1, firstIndex = 0, secondIndex = 0;
    ImVec2 top, bottom;  // the column's smallest and largest screen y
    int topIndex = 0, bottomIndex = 0;
    auto emit = [&] {
      if (column < 0) return;
      firstIndex = std::min(topIndex, bottomIndex), secondIndex = std::max(topIndex, bottomIndex);
      run.push_back(firstIndex == topIndex ? top : bottom);
      if (secondIndex != firstIndex) run.push_back(secondIndex == topIndex ? top : bottom);
      column = -1;
    };
    for (int k = 0; k < h.count; ++k) {
      const float v = h.values[l.series][at(k)];
      if (!std::isfinite(v)) {
        emit();
        flush(l);
        continue;
      }
      const ImVec2 p = map(h.t[at(k)], std::clamp(v, lo, hi));
      const int c = static_cast<int>(std::floor(p.x));
      if (c != column) {
        emit();
        column = c, top = bottom = p, topIndex = bottomIndex = k;
      } else if (p.y < top.y) {
        top = p, topIndex = k;
      } else if (p.y > bottom.y) {
        bottom = p, bottomIndex = k;
      }
    }
    emit();
    flush(l);
  }
  std::snprintf(text, sizeof text, "t %.1f .. %.1f s", t0, t1);
  draw->AddText(ImVec2(p0.x + 4, bottom + 1), IM_COL32(90, 90, 90, 255), text);
}

}  // namespace cablelab::ui
