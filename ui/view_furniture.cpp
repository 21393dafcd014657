#include "ui/view_furniture.h"

#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/colormap.h"
#include "ui/palette.h"
#include "ui/renderer.h"

namespace cablelab::ui {
namespace {

constexpr const char* kPausedText = "PAUSED";
constexpr float kPausedFont = 2.5f;  // the PAUSED sign's size in text lines

std::string format(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value);
  return buffer;
}

float textWidth(const std::string& s, bool text, float lineHeight) {
  return text ? ImGui::CalcTextSize(s.c_str()).x : 0.55f * lineHeight * s.size();
}

void glColour(const Colour& c) {
  glColor4f(c[0], c[1], c[2], c[3]);
}

void quad(float x0, float y0, float x1, float y1) {
  glBegin(GL_QUADS);
  glVertex2f(x0, y0);
  glVertex2f(x1, y0);
  glVertex2f(x1, y1);
  glVertex2f(x0, y1);
  glEnd();
}

double gridStepFor(const Camera& cam) {
  return niceCeil(60.0 * cam.metresPerPixel);
}

/// A long note wraps in a narrow view.
float notesWrap(const FurnitureLayout& l) {
  return std::max(l.w - 16, 4 * l.lineHeight);
}

std::string colourBarTitle(const RenderOptions& options) {
  return options.tensionLocked ? "tension (N), locked" : "tension (N)";
}

std::vector<MarkerKeyRow> keyRows(const World& world, const Overlay& overlay,
                                  const RenderOptions& options) {
  using Sample = MarkerKeyRow::Sample;
  std::vector<MarkerKeyRow> rows;
  bool point = false, polygon = false, stretched = false;
  for (const CableDef& c : world.scene().cables)
    for (const PulleyDef& p : c.pulleys)
      (p.kind == PulleyDef::Kind::Point ? point : polygon) = true;
  for (int i = 0; i < world.cableCount(); ++i) stretched |= overstretched(world.cable(i));
  const Colour dark{0.15f, 0.15f, 0.15f, 1};
  if (options.wrapPoints && world.cableCount() > 0) {
    rows.push_back({Sample::Anchor, dark, "cable end"});
    rows.push_back({Sample::WrapPoint, dark, "wrap point"});
  }
  if (point) rows.push_back({Sample::PointPulley, kPulley, "point pulley"});
  if (polygon) {
    rows.push_back({Sample::PulleyInUse, kPulley, "pulley, cable on it"});
    rows.push_back({Sample::PulleyIdle, kPulleyIdle, "pulley, cable off it"});
  }
  bool revolute = false;
  for (const JointDef& j : world.scene().joints) revolute |= j.kind == JointDef::Kind::Revolute;
  if (revolute) rows.push_back({Sample::PointPulley, kJoint, "revolute joint"});
  if (options.forces && world.cableCount() > 0)
    rows.push_back({Sample::Arrow, kForceArrow, "cable force"});
  if (options.overstretch && stretched)
    rows.push_back({Sample::Stretch, kStretchHalo, "overstretched cable"});
  for (const Overlay::Key& k : overlay.keys)
    rows.push_back({k.marker == Overlay::Key::Marker::Arrow ? Sample::Arrow : Sample::Cross,
                    k.colour, k.label});
  return rows;
}

void layoutBars(FurnitureLayout& l, const World& world, const RenderOptions& options,
                const Camera& cam, bool text) {
  const float lh = l.lineHeight;
  if (options.grid) {
    const double step = gridStepFor(cam);
    const float length = static_cast<float>(step / cam.metresPerPixel);
    const float x0 = l.x + 16, y0 = l.y + l.h - 18, half = std::max(6.0f, 0.5f * lh);
    const float label = textWidth(format("%g", step) + " m", text, lh);
    l.scaleBar = {x0 - 4, y0 - half - 1, x0 + length + 6 + label + 4, y0 + half + 1};
  }
  if (!options.legend || world.cableCount() == 0) return;
  l.barHeight = std::max(10.0f, 0.7f * lh);
  l.barWidth = std::clamp(0.3f * l.w, 90.0f, 12 * lh);
  l.slackWidth = text ? ImGui::CalcTextSize("slack").x + 34 : 80;
  const float title = textWidth(colourBarTitle(options), text, lh);
  auto place = [&] {
    l.barX = l.x + l.w - l.barWidth - 24;
    l.barY = l.y + l.h - 1.6f * lh - l.barHeight;
    const float left = l.barX - l.slackWidth - 8;
    const float right =
        std::max(l.barX + l.barWidth + 20, (options.tensionLocked ? left : l.barX) + title + 4);
    // A title wider than the bar would reach past the view's edge: the whole piece moves left.
    const float over = std::max(0.0f, right - (l.x + l.w - 2));
    l.barX -= over;
    l.colourBar = {left - over, l.barY - 1.5f * lh, right - over, l.barY + l.barHeight + 1.5f * lh};
  };
  place();
  if (l.scaleBar.empty() || !l.colourBar.overlaps(l.scaleBar)) return;
  // The scale bar reaches under the colour bar: a narrower bar, else the bar above it.
  const float narrower = l.barWidth - static_cast<float>(l.scaleBar.x1 + 8 - l.colourBar.x0);
  if (narrower >= 90) {
    l.barWidth = narrower;
    place();
    return;
  }
  const float lift = static_cast<float>(l.colourBar.y1 - l.scaleBar.y0) + 6;
  l.barY -= lift;
  l.colourBar.y0 -= lift;
  l.colourBar.y1 -= lift;
}

/// The notes top left, below a collapsed panel's title bar (`keyTop`) that may reach over them.
void layoutNotes(FurnitureLayout& l, const Overlay& overlay, const RenderOptions& options,
                 bool text) {
  if (!text || overlay.notes.empty()) return;
  float width = 0, height = 0;
  for (const std::string& n : overlay.notes) {
    const ImVec2 size = ImGui::CalcTextSize(n.c_str(), nullptr, false, notesWrap(l));
    width = std::max(width, size.x);
    height += size.y + 2;
  }
  const float y0 = l.y + 8 + options.keyTop;
  l.notes = {l.x + 8, y0, l.x + 8 + width, y0 + height};
}

/// The key's rows in `columns` columns, its top right corner at (x1, y0).
LabelBox keyBoxAt(const FurnitureLayout& l, float x1, float y0, int columns) {
  const int perColumn = (static_cast<int>(l.keyRows.size()) + columns - 1) / columns;
  return {x1 - columns * l.keyColumnWidth - 8, y0, x1, y0 + perColumn * l.keyRowHeight + 8};
}

void layoutKey(FurnitureLayout& l, const World& world, const Overlay& overlay,
               const RenderOptions& options, bool text, const LabelBox& scene) {
  if (!options.markerLegend || !text) return;
  l.keyRows = keyRows(world, overlay, options);
  if (l.keyRows.empty()) return;
  const float lh = l.lineHeight, s = options.lineScale;
  l.keySampleWidth = 24 * s;
  float width = 0;
  for (const MarkerKeyRow& r : l.keyRows)
    width = std::max(width, ImGui::CalcTextSize(r.label.c_str()).x);
  l.keyRowHeight = std::max(lh + 2, 16 * s);
  l.keyColumnWidth = width + l.keySampleWidth + 16;
  const float x1 = l.x + l.w - 8;
  float y0 = l.y + 8 + options.keyTop;
  if (!l.notes.empty() && l.notes.x1 + 8 > x1 - l.keyColumnWidth - 8)
    y0 = static_cast<float>(l.notes.y1) + 6;
  l.keyAsColumn = keyBoxAt(l, x1, y0, 1);
  const auto reachesBars = [&](const LabelBox& key) {
    return (!l.colourBar.empty() && key.overlaps(l.colourBar)) ||
           (!l.scaleBar.empty() && key.overlaps(l.scaleBar)) || key.y1 > l.y + l.h;
  };
  if (!options.keyGivesWay) {
    // Out of presentation mode the key gives way on a small view, where it would be too wide
    // or reach the bars (the View toggle brings it back once the window is larger).
    if (l.keyColumnWidth > 0.4f * l.w || reachesBars(l.keyAsColumn)) {
      l.keyRows.clear();
      return;
    }
    l.key = l.keyAsColumn;
    return;
  }
  // Presentation mode: every marker drawn keeps its key in view, off the scene's moving parts:
  // a column top right, else a strip along the top in as many columns as the view's width
  // holds (the presentation fit leaves room for one of them, ui/presentation.h, on a window
  // large enough for both).
  const int columns = std::clamp(static_cast<int>((l.w - 24) / l.keyColumnWidth), 1,
                                 static_cast<int>(l.keyRows.size()));
  float stripTop = y0;
  if (!l.notes.empty() && l.notes.x1 + 8 > x1 - columns * l.keyColumnWidth - 8)
    stripTop = static_cast<float>(l.notes.y1) + 6;
  l.keyAsStrip = keyBoxAt(l, x1, stripTop, columns);
  l.keyColumns = 1;
  l.key = l.keyAsColumn;
  const auto onScene = [&](const LabelBox& key) {
    return scene.empty() ? 0.0 : key.overlapArea(scene);
  };
  if (onScene(l.keyAsColumn) == 0 && !reachesBars(l.keyAsColumn)) return;
  if (onScene(l.keyAsStrip) < onScene(l.keyAsColumn) || reachesBars(l.keyAsColumn)) {
    l.keyColumns = columns;
    l.key = l.keyAsStrip;
  }
  // Neither keeps off the scene: a window too small for both, or a body dragged under the key.
  // The key gives way (its rows are kept: the fit makes room when they change).
  l.keyOnScene = onScene(l.key) > 0;
  if (l.keyOnScene) l.key = {};
}

void layoutTexts(FurnitureLayout& l, const Overlay& overlay, const RenderOptions& options,
                 bool text) {
  const float lh = l.lineHeight;
  if (text && !overlay.banner.empty()) {
    float x0 = l.x + 8;
    float y0 = l.notes.empty() ? l.y + 6 + options.keyTop : static_cast<float>(l.notes.y1) + 6;
    float right = l.key.empty() ? l.x + l.w - 8 : static_cast<float>(l.key.x0) - 8;
    if (!l.key.empty() && right - x0 < 16 * lh) {  // too narrow beside the key: below it
      y0 = std::max(y0, static_cast<float>(l.key.y1) + 6);
      right = l.x + l.w - 8;
    }
    l.bannerWrap = std::max(right - x0 - 20, 4 * lh);
    const ImVec2 size = ImGui::CalcTextSize(overlay.banner.c_str(), nullptr, false, l.bannerWrap);
    const float w = size.x + 20, bx = x0 + std::max(0.0f, 0.5f * (right - x0 - w));
    l.banner = {bx, y0, bx + w, y0 + size.y + 10};
  }
  if (options.paused) {
    l.pausedSize = kPausedFont * lh;
    const float w = text ? ImGui::GetFont()->CalcTextSizeA(l.pausedSize, 1e9f, 0, kPausedText).x
                         : 0.6f * l.pausedSize * 6;
    // In the bars' row between the bars, which the fit keeps free of the scene (a ground sits
    // just above it); above the bars where they leave no room.
    const float bottom = l.y + l.h - 6, x0 = l.x + 0.5f * (l.w - w) - 10;
    l.paused = {x0, bottom - l.pausedSize - 8, x0 + w + 20, bottom};
    bool onABar = false;
    float above = bottom;
    for (const LabelBox* b : {&l.scaleBar, &l.colourBar})
      if (!b->empty()) {
        onABar |= b->overlaps(l.paused);
        above = std::min(above, static_cast<float>(b->y0) - 6);
      }
    if (onABar) l.paused = {x0, above - l.pausedSize - 8, x0 + w + 20, above};
  }
}

void drawScaleBar(const FurnitureLayout& l, const Camera& cam, ImDrawList* text) {
  const double step = gridStepFor(cam);
  const float length = static_cast<float>(step / cam.metresPerPixel);
  const float x0 = l.x + 16, y0 = l.y + l.h - 18;
  glLineWidth(2.0f);
  glColor4f(0.15f, 0.15f, 0.15f, 1);
  glBegin(GL_LINES);
  glVertex2f(x0, y0);
  glVertex2f(x0 + length, y0);
  glVertex2f(x0, y0 - 5);
  glVertex2f(x0, y0 + 5);
  glVertex2f(x0 + length, y0 - 5);
  glVertex2f(x0 + length, y0 + 5);
  glEnd();
  if (text)
    text->AddText(ImVec2(x0 + length + 6, y0 - 0.5f * l.lineHeight), IM_COL32(40, 40, 40, 255),
                  (format("%g", step) + " m").c_str());
}

void drawTensionBar(const FurnitureLayout& l, const RenderOptions& options, double scale,
                    ImDrawList* text) {
  const float lh = l.lineHeight, barW = l.barWidth, barH = l.barHeight, slackW = l.slackWidth;
  const float x0 = l.barX, y0 = l.barY;
  glColor4f(kBackground[0], kBackground[1], kBackground[2], 0.85f);
  quad(static_cast<float>(l.colourBar.x0), static_cast<float>(l.colourBar.y0),
       static_cast<float>(l.colourBar.x1), static_cast<float>(l.colourBar.y1));
  glBegin(GL_QUADS);
  const int n = 32;
  for (int k = 0; k < n; ++k) {
    const float a = static_cast<float>(k) / n, b = static_cast<float>(k + 1) / n;
    glColour(tensionColour(a));
    glVertex2f(x0 + barW * a, y0 + barH);
    glVertex2f(x0 + barW * a, y0);
    glColour(tensionColour(b));
    glVertex2f(x0 + barW * b, y0);
    glVertex2f(x0 + barW * b, y0 + barH);
  }
  glEnd();
  glLineWidth(1.0f);
  glColor4f(0.2f, 0.2f, 0.2f, 1);
  glBegin(GL_LINE_LOOP);
  glVertex2f(x0, y0);
  glVertex2f(x0 + barW, y0);
  glVertex2f(x0 + barW, y0 + barH);
  glVertex2f(x0, y0 + barH);
  glEnd();
  glBegin(GL_LINES);
  for (int k = 0; k <= 4; ++k) {
    glVertex2f(x0 + barW * k / 4.0f, y0 + barH);
    glVertex2f(x0 + barW * k / 4.0f, y0 + barH + 3);
  }
  // Slack sample, left of the bar: a dashed grey stroke.
  glColor4f(kSlack[0], kSlack[1], kSlack[2], 1);
  for (int k = 0; k < 3; ++k) {
    glVertex2f(x0 - slackW + 8.0f * k, y0 + 0.5f * barH);
    glVertex2f(x0 - slackW + 5 + 8.0f * k, y0 + 0.5f * barH);
  }
  glEnd();
  if (!text) return;
  const ImU32 ink = IM_COL32(40, 40, 40, 255);
  const float titleX = options.tensionLocked ? static_cast<float>(l.colourBar.x0) + 4 : x0;
  text->AddText(ImVec2(titleX, y0 - 1.25f * lh), ink, colourBarTitle(options).c_str());
  text->AddText(ImVec2(x0 - slackW + 28, y0 + 0.5f * (barH - lh)), ink, "slack");
  for (int k = 0; k <= 4; k += 2) {
    const std::string label = format("%.3g", scale * k / 4);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    text->AddText(ImVec2(x0 + barW * k / 4.0f - 0.5f * w, y0 + barH + 4), ink, label.c_str());
  }
}

void drawSample(const MarkerKeyRow& row, float cx, float cy, float s) {
  using Sample = MarkerKeyRow::Sample;
  const Colour& c = row.colour;
  auto disc = [&](float r, const Colour& fill) {
    glColour(fill);
    glBegin(GL_TRIANGLE_FAN);
    for (int k = 0; k < 20; ++k)
      glVertex2f(cx + r * std::cos(2 * M_PI * k / 20), cy + r * std::sin(2 * M_PI * k / 20));
    glEnd();
  };
  auto segment = [&](float x0, float y0, float x1, float y1, float width) {
    glLineWidth(width * s);
    glColour(c);
    glBegin(GL_LINES);
    glVertex2f(x0, y0);
    glVertex2f(x1, y1);
    glEnd();
  };
  const float h = 8 * s;
  switch (row.sample) {
    case Sample::Anchor:
      disc(3.5f * s, c);
      break;
    case Sample::WrapPoint:
      glColour(c);
      quad(cx - 3 * s, cy - 3 * s, cx + 3 * s, cy + 3 * s);
      break;
    case Sample::PointPulley:
      disc(6 * s, c);
      disc(3.5f * s, {1, 1, 1, 1});
      break;
    case Sample::PulleyInUse:
    case Sample::PulleyIdle:
      segment(cx - h, cy, cx + h, cy, 2.5f);
      break;
    case Sample::Stretch:
      segment(cx - h, cy, cx + h, cy, 10.0f);
      break;
    case Sample::Arrow:
      segment(cx - h, cy, cx + h, cy, 2);
      segment(cx + h, cy, cx + h - 0.6f * h, cy - 0.4f * h, 2);
      segment(cx + h, cy, cx + h - 0.6f * h, cy + 0.4f * h, 2);
      break;
    case Sample::Cross:
    case Sample::DashedCross:
      segment(cx - 0.8f * h, cy - 0.8f * h, cx + 0.8f * h, cy + 0.8f * h, 2.5f);
      segment(cx - 0.8f * h, cy + 0.8f * h, cx + 0.8f * h, cy - 0.8f * h, 2.5f);
      break;
  }
}

void drawMarkerKey(const FurnitureLayout& l, const RenderOptions& options, ImDrawList* text) {
  if (!text || l.key.empty()) return;
  const float x0 = static_cast<float>(l.key.x0), y0 = static_cast<float>(l.key.y0);
  glColor4f(kBackground[0], kBackground[1], kBackground[2], 0.85f);
  quad(x0, y0, static_cast<float>(l.key.x1), static_cast<float>(l.key.y1));
  const size_t perColumn = (l.keyRows.size() + l.keyColumns - 1) / l.keyColumns;
  for (size_t k = 0; k < l.keyRows.size(); ++k) {
    const float cx = x0 + (k / perColumn) * l.keyColumnWidth;
    const float cy = y0 + 4 + (k % perColumn + 0.5f) * l.keyRowHeight;
    drawSample(l.keyRows[k], cx + 6 + 0.5f * l.keySampleWidth, cy, options.lineScale);
    text->AddText(ImVec2(cx + 10 + l.keySampleWidth, cy - 0.5f * l.lineHeight),
                  IM_COL32(40, 40, 40, 255), l.keyRows[k].label.c_str());
  }
}

/// A pale yellow box with a dark orange rim.
void drawBanner(const FurnitureLayout& l, const std::string& banner, ImDrawList* text) {
  if (l.banner.empty() || !text) return;
  const float x0 = static_cast<float>(l.banner.x0), y0 = static_cast<float>(l.banner.y0);
  const float x1 = static_cast<float>(l.banner.x1), y1 = static_cast<float>(l.banner.y1);
  glColor4f(1.0f, 0.91f, 0.55f, 0.95f);
  quad(x0, y0, x1, y1);
  glLineWidth(1.5f);
  glColor4f(0.7f, 0.45f, 0.0f, 1);
  glBegin(GL_LINE_LOOP);
  glVertex2f(x0, y0);
  glVertex2f(x1, y0);
  glVertex2f(x1, y1);
  glVertex2f(x0, y1);
  glEnd();
  text->AddText(nullptr, 0, ImVec2(x0 + 10, y0 + 5), IM_COL32(90, 50, 0, 255), banner.c_str(),
                nullptr, l.bannerWrap);
}

void drawPaused(const FurnitureLayout& l, ImDrawList* text) {
  if (l.paused.empty() || !text) return;
  glColor4f(kBackground[0], kBackground[1], kBackground[2], 0.8f);
  quad(static_cast<float>(l.paused.x0), static_cast<float>(l.paused.y0),
       static_cast<float>(l.paused.x1), static_cast<float>(l.paused.y1));
  text->AddText(nullptr, l.pausedSize,
                ImVec2(static_cast<float>(l.paused.x0) + 10, static_cast<float>(l.paused.y0) + 4),
                IM_COL32(150, 30, 30, 230), kPausedText);
}

}  // namespace

std::vector<LabelBox> FurnitureLayout::occupied() const {
  std::vector<LabelBox> boxes;
  for (const LabelBox* b : {&scaleBar, &colourBar, &key, &notes, &banner, &paused})
    if (!b->empty()) boxes.push_back(*b);
  return boxes;
}

FurnitureLayout layoutFurniture(const World& world, const Overlay& overlay,
                                const RenderOptions& options, const Camera& camera, bool text,
                                const LabelBox& scene) {
  FurnitureLayout l;
  const bool whole = options.freeWidth <= 0 || options.freeHeight <= 0;
  l.x = whole ? 0.0f : options.freeX;
  l.y = whole ? 0.0f : options.freeY;
  l.w = whole ? static_cast<float>(camera.width) : options.freeWidth;
  l.h = whole ? static_cast<float>(camera.height) : options.freeHeight;
  l.lineHeight = text ? ImGui::GetTextLineHeight() : 13.0f;
  layoutBars(l, world, options, camera, text);
  layoutNotes(l, overlay, options, text);
  layoutKey(l, world, overlay, options, text, scene);
  layoutTexts(l, overlay, options, text);
  return l;
}

void drawFurniture(const FurnitureLayout& l, const Overlay& overlay, const RenderOptions& options,
                   double scale, const Camera& camera, ImDrawList* text) {
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, camera.width, camera.height, 0, -1, 1);
  if (text && !l.notes.empty()) {
    float y = static_cast<float>(l.notes.y0);
    for (const std::string& n : overlay.notes) {
      text->AddText(nullptr, 0, ImVec2(static_cast<float>(l.notes.x0), y),
                    IM_COL32(40, 40, 40, 255), n.c_str(), nullptr, notesWrap(l));
      y += ImGui::CalcTextSize(n.c_str(), nullptr, false, notesWrap(l)).y + 2;
    }
  }
  if (!l.scaleBar.empty()) drawScaleBar(l, camera, text);
  if (!l.colourBar.empty()) drawTensionBar(l, options, scale, text);
  drawMarkerKey(l, options, text);
  drawBanner(l, overlay.banner, text);
  drawPaused(l, text);
}

}  // namespace cablelab::ui
