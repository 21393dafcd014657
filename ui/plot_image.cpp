// Plots drawn on the CPU, and their CSV (ui/plot_image.h).
#include "ui/plot_image.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "ui/draw_raster.h"
#include "ui/plot_draw.h"

namespace cablelab::ui {
namespace {

/// A Dear ImGui context for one picture, the caller's restored when it goes.
class PictureContext {
 public:
  PictureContext(int width, int height, float fontPixels)
      : previous_(ImGui::GetCurrentContext()), atlas_(), context_(ImGui::CreateContext(&atlas_)) {
    ImGui::SetCurrentContext(context_);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
    io.DeltaTime = 1.0f / 60.0f;
    ImFontConfig font;
    font.SizePixels = fontPixels;
    atlas_.AddFontDefault(&font);
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    atlas_.GetTexDataAsRGBA32(&pixels, &w, &h);
    texture_.width = w;
    texture_.height = h;
    texture_.rgba.assign(pixels, pixels + static_cast<size_t>(w) * h * 4);
    atlas_.SetTexID(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(1)));
  }
  ~PictureContext() {
    ImGui::DestroyContext(context_);
    ImGui::SetCurrentContext(previous_);
  }
  PictureContext(const PictureContext&) = delete;
  PictureContext& operator=(const PictureContext&) = delete;
  const Image& texture() const { return texture_; }

 private:
  ImGuiContext* previous_;
  ImFontAtlas atlas_;
  ImGuiContext* context_;
  Image texture_;
};

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

float slideScale(int width, int height) {
  return std::min(width / 640.0f, height / 400.0f);
}

Image renderPlotImage(const Plot& plot, int width, int height) {
  const float scale = slideScale(width, height);
  checkPlot(plot, width, height);
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(static_cast<size_t>(width) * height * 4, 255);
  PictureContext context(width, height, 13.0f * scale);
  ImGui::NewFrame();
  drawPlot(ImGui::GetBackgroundDrawList(), plot, width, height, scale);
  ImGui::Render();
  rasterize(*ImGui::GetDrawData(), context.texture(), image);
  return image;
}

void writePlotCsv(const Plot& plot, const std::string& path) {
  if (plot.series.empty()) throw std::runtime_error(path + ": the plot has no data");
  const std::vector<double>& x = plot.series.front().x;
  for (const PlotSeries& s : plot.series)
    if (s.x.size() != x.size() || s.y.size() != x.size())
      throw std::runtime_error(path + ": series '" + s.label + "' has another length");
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the file");
  out << csvField(plot.xLabel);
  for (const PlotSeries& s : plot.series) out << ',' << csvField(s.label);
  out << '\n';
  char number[40];
  auto field = [&](double v) {
    if (!std::isfinite(v)) return std::string();
    std::snprintf(number, sizeof number, "%.17g", v);
    return std::string(number);
  };
  for (size_t i = 0; i < x.size(); ++i) {
    out << field(x[i]);
    for (const PlotSeries& s : plot.series) out << ',' << field(s.y[i]);
    out << '\n';
  }
  if (!out) throw std::runtime_error(path + ": cannot write the file");
}

}  // namespace cablelab::ui
