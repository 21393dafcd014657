// GIF palettes for rendered frames: the 256 most common colours of a frame, every other colour
// drawn as the nearest of them. A rendered scene is mostly flat fills, so its common colours
// are exactly the fills, the background and the cables; a median cut (giflib's
// GifQuantizeBuffer) splits colour space by pixel count instead and merged a light body fill
// into the background (a weight drawn as an outline).
//
// Needs: ui/image.h only. Colours are grouped by their top 5 bits per channel (32768 groups);
// a group's palette colour is the mean of its pixels, exact for a flat fill.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "ui/image.h"

namespace cablelab::ui {

/// A rectangle of an image as palette indices.
struct IndexedPixels {
  std::vector<std::array<std::uint8_t, 3>> palette;  ///< 1..256 RGB entries
  std::vector<std::uint8_t> indices;                 ///< w x h, top row first
};

/// The w x h rectangle of `image` at (x, y) as indices into its own palette of at most 256
/// colours (the rectangle must lie inside the image).
IndexedPixels indexColours(const Image& image, int x, int y, int w, int h);

}  // namespace cablelab::ui
