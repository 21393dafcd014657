// Palette: the renderer's colours, shared by the scene (renderer.cpp) and the screen-space
// pieces over it (view_furniture.cpp), so that a key's sample is the colour it explains.
//
// Needs: ui/overlay.h (Colour) and Dear ImGui's ImU32 only.
#pragma once

#include <imgui.h>

#include <algorithm>

#include "ui/overlay.h"

namespace cablelab::ui {

inline constexpr Colour kBackground{0.97f, 0.97f, 0.95f, 1};
inline constexpr Colour kSlack{0.55f, 0.55f, 0.55f, 1};
inline constexpr Colour kPulley{0.9f, 0.45f, 0.0f, 1};
inline constexpr Colour kPulleyIdle{0.95f, 0.75f, 0.55f, 1};  // a pulley the cable is off now
inline constexpr Colour kJoint{0.25f, 0.25f, 0.3f, 1};
inline constexpr Colour kStretchHalo{0.9f, 0.0f, 0.1f, 0.35f};
inline constexpr Colour kForceArrow{0.55f, 0.1f, 0.6f, 1};

inline ImU32 toImU32(const Colour& c) {
  auto b = [](float v) { return static_cast<int>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
  return IM_COL32(b(c[0]), b(c[1]), b(c[2]), b(c[3]));
}

}  // namespace cablelab::ui
