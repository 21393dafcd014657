// Dear ImGui draw data drawn on the CPU into an Image: pictures larger than the window (a plot at
// slide size) from a program that links libGL, where the OSMesa renderer cannot run (README.md).
//
// Needs: Dear ImGui (draw data only; no backend, no GL).
#pragma once

#include <imgui.h>

#include "ui/image.h"

namespace cablelab::ui {

/// Draws every triangle of `data` into `image` (alpha blended over what is there), each within
/// its command's clip rectangle, textured by `texture` (the font atlas as
/// ImFontAtlas::GetTexDataAsRGBA32 gives it; nearest texel), colours interpolated across the
/// triangle (Dear ImGui's anti-aliased edges fade to transparent). Pixel (0, 0) is display point
/// (0, 0): `data.DisplayPos` is taken to be the origin.
void rasterize(const ImDrawData& data, const Image& texture, Image& image);

}  // namespace cablelab::ui
