// The lecture GUI tests' checks on a reported view (tests/ui/lecture_gui_test.cpp): screen boxes
// from its JSON, a line through a box, pixels of a colour inside a box of a screenshot.
//
// Needs: nlohmann/json, ui/image.h. Header-only, in the lecture tests' own namespace.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "ui/image.h"

namespace cablelab::test {
namespace lecture_gui_test {

struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool overlaps(const Box& o) const {
    return std::min(x1, o.x1) > std::max(x0, o.x0) && std::min(y1, o.y1) > std::max(y0, o.y0);
  }
};

inline std::vector<Box> boxes(const nlohmann::json& list) {
  std::vector<Box> out;
  for (const auto& b : list) out.push_back({b[0], b[1], b[2], b[3]});
  return out;
}

/// True when the segment [x0, y0, x1, y1] (px) passes through the inside of `b` (1 px in from
/// its edges), sampled every half pixel.
inline bool crosses(const nlohmann::json& line, const Box& b) {
  const double x0 = line[0], y0 = line[1], x1 = line[2], y1 = line[3];
  const int n = 2 * static_cast<int>(std::hypot(x1 - x0, y1 - y0)) + 2;
  for (int k = 0; k <= n; ++k) {
    const double x = x0 + (x1 - x0) * k / n, y = y0 + (y1 - y0) * k / n;
    if (x > b.x0 + 1 && x < b.x1 - 1 && y > b.y0 + 1 && y < b.y1 - 1) return true;
  }
  return false;
}

/// Pixels inside `box` (px) that are red in `shot` (red above green and blue by 20 levels, as
/// the drag arrow at its force limit, even seen through the colour bar's backing) and not in
/// `before` (the colour bar's own red end).
inline int newRedPixels(const ui::Image& before, const ui::Image& shot, const Box& box) {
  const auto red = [](const std::uint8_t* p) { return p[0] - std::max(p[1], p[2]) > 20; };
  int count = 0;
  for (int y = static_cast<int>(box.y0) + 1; y < static_cast<int>(box.y1) - 1; ++y)
    for (int x = static_cast<int>(box.x0) + 1; x < static_cast<int>(box.x1) - 1; ++x)
      count += red(shot.pixel(x, y)) && !red(before.pixel(x, y));
  return count;
}

/// Pixels inside `box` (px) of `shot` as dark as text (no channel above 110).
inline int darkPixels(const ui::Image& shot, const Box& box) {
  int count = 0;
  for (int y = std::max(0, static_cast<int>(box.y0));
       y < std::min(shot.height, static_cast<int>(box.y1)); ++y)
    for (int x = std::max(0, static_cast<int>(box.x0));
         x < std::min(shot.width, static_cast<int>(box.x1)); ++x) {
      const std::uint8_t* p = shot.pixel(x, y);
      count += std::max({p[0], p[1], p[2]}) <= 110;
    }
  return count;
}

}  // namespace lecture_gui_test
}  // namespace cablelab::test
