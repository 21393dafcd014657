// Image: an RGBA8 pixel buffer with PNG reading and writing (libpng).
//
// Needs: libpng (linked by cablelab_offscreen). Rows are stored top row first.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cablelab::ui {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes, top row first

  const std::uint8_t* pixel(int x, int y) const {
    return &rgba[(static_cast<size_t>(y) * width + x) * 4];
  }
  std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
};

/// Writes `image` as an 8-bit RGBA PNG; throws std::runtime_error naming `path` on failure.
void writePng(const Image& image, const std::string& path);

/// Reads any PNG as 8-bit RGBA; throws std::runtime_error naming `path` on failure.
Image readPng(const std::string& path);

/// The w x h rectangle of `image` at (x, y) (top-left origin), clamped to the image.
Image cropped(const Image& image, int x, int y, int w, int h);

/// Reverses the row order in place (OpenGL reads rows bottom first).
void flipRows(Image& image);

}  // namespace cablelab::ui
