// Image: an RGBA8 pixel buffer with PNG reading and writing (libpng), and the one image
// comparison (`cablelab snapshot --compare`, the golden-image tests).
//
// Needs: libpng (linked by cablelab_render). Rows are stored top row first.
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

/// Reads any PNG as 8-bit RGBA. A missing file, a directory or a file that is not a PNG is an
/// InputError naming `path` ("REF.png: (file): not a PNG image: ..."), as users name these files.
Image readPng(const std::string& path);

/// How `actual` differs from `expected` (the same size): a pixel differs when its largest
/// red, green or blue difference exceeds `threshold` levels of 255 (alpha is not compared).
struct ImageComparison {
  long differing = 0;  ///< pixels beyond the threshold
  long pixels = 0;     ///< width x height
  /// differing / pixels, in [0, 1]
  double share() const { return pixels > 0 ? static_cast<double>(differing) / pixels : 0; }
  /// Where they differ: `expected` as grey in [140, 254], differing pixels red (230, 0, 0).
  Image diff;
};

/// Compares two images of the same size (throws std::invalid_argument otherwise).
ImageComparison compareImages(const Image& expected, const Image& actual, int threshold);

/// The w x h rectangle of `image` at (x, y) (top-left origin), clamped to the image.
Image cropped(const Image& image, int x, int y, int w, int h);

/// Reverses the row order in place (OpenGL reads rows bottom first).
void flipRows(Image& image);

}  // namespace cablelab::ui
