// A triangle rasterizer for Dear ImGui draw data (ui/draw_raster.h).
#include "ui/draw_raster.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace cablelab::ui {
namespace {

/// Twice the signed area of (a, b, p).
float edge(const ImVec2& a, const ImVec2& b, float px, float py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

std::array<float, 4> unpack(ImU32 c) {
  return {static_cast<float>((c >> IM_COL32_R_SHIFT) & 0xFF),
          static_cast<float>((c >> IM_COL32_G_SHIFT) & 0xFF),
          static_cast<float>((c >> IM_COL32_B_SHIFT) & 0xFF),
          static_cast<float>((c >> IM_COL32_A_SHIFT) & 0xFF)};
}

struct Clip {
  int x0, y0, x1, y1;  ///< pixels [x0, x1) x [y0, y1)
};

void triangle(const ImDrawVert& a, const ImDrawVert& b, const ImDrawVert& c, const Clip& clip,
              const Image& texture, Image& image) {
  const float area = edge(a.pos, b.pos, c.pos.x, c.pos.y);
  if (std::abs(area) < 1e-12f) return;
  const int x0 =
      std::max(clip.x0, static_cast<int>(std::floor(std::min({a.pos.x, b.pos.x, c.pos.x}))));
  const int x1 =
      std::min(clip.x1, static_cast<int>(std::ceil(std::max({a.pos.x, b.pos.x, c.pos.x}))));
  const int y0 =
      std::max(clip.y0, static_cast<int>(std::floor(std::min({a.pos.y, b.pos.y, c.pos.y}))));
  const int y1 =
      std::min(clip.y1, static_cast<int>(std::ceil(std::max({a.pos.y, b.pos.y, c.pos.y}))));
  const auto ca = unpack(a.col), cb = unpack(b.col), cc = unpack(c.col);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const float px = x + 0.5f, py = y + 0.5f;
      const float wa = edge(b.pos, c.pos, px, py) / area;
      const float wb = edge(c.pos, a.pos, px, py) / area;
      const float wc = 1 - wa - wb;
      if (wa < 0 || wb < 0 || wc < 0) continue;
      const float u = wa * a.uv.x + wb * b.uv.x + wc * c.uv.x;
      const float v = wa * a.uv.y + wb * b.uv.y + wc * c.uv.y;
      const int tx = std::clamp(static_cast<int>(u * texture.width), 0, texture.width - 1);
      const int ty = std::clamp(static_cast<int>(v * texture.height), 0, texture.height - 1);
      const std::uint8_t* t = texture.pixel(tx, ty);
      std::array<float, 4> s;
      for (int k = 0; k < 4; ++k) s[k] = (wa * ca[k] + wb * cb[k] + wc * cc[k]) * t[k] / 255.0f;
      const float alpha = s[3] / 255.0f;
      std::uint8_t* d = image.pixel(x, y);
      for (int k = 0; k < 3; ++k)
        d[k] = static_cast<std::uint8_t>(std::lround(s[k] * alpha + d[k] * (1 - alpha)));
      d[3] = static_cast<std::uint8_t>(std::lround(s[3] + d[3] * (1 - alpha)));
    }
}

}  // namespace

void rasterize(const ImDrawData& data, const Image& texture, Image& image) {
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      if (cmd.UserCallback) continue;
      const ImVec4 r = cmd.ClipRect;
      const Clip clip{std::max(0, static_cast<int>(std::floor(r.x))),
                      std::max(0, static_cast<int>(std::floor(r.y))),
                      std::min(image.width, static_cast<int>(std::ceil(r.z))),
                      std::min(image.height, static_cast<int>(std::ceil(r.w)))};
      for (unsigned e = 0; e + 2 < cmd.ElemCount; e += 3) {
        const ImDrawIdx* idx = &list.IdxBuffer[static_cast<int>(cmd.IdxOffset + e)];
        const ImDrawVert* v = &list.VtxBuffer[static_cast<int>(cmd.VtxOffset)];
        triangle(v[idx[0]], v[idx[1]], v[idx[2]], clip, texture, image);
      }
    }
  }
}

}  // namespace cablelab::ui
