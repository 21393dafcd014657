#include "ui/image.h"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "engine/core/error.h"
#include "engine/core/file_input.h"

namespace cablelab::ui {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open(const std::string& path, const char* mode) {
  File f(std::fopen(path.c_str(), mode));
  if (!f) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  return f;
}

}  // namespace

void writePng(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
    throw std::runtime_error(path + ": cannot write an empty or inconsistent image");
  File file = open(path, "wb");
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGBA;
  if (!png_image_write_to_stdio(&png, file.get(), 0, image.rgba.data(), 0, nullptr))
    throw std::runtime_error(path + ": PNG write failed: " + png.message);
  if (std::fflush(file.get()) != 0)
    throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
}

Image readPng(const std::string& path) {
  const std::string bytes = readInputFile(path);  // a missing file or a directory says so
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()))
    throw InputError(path, "(file)",
                     std::string("not a PNG image: ") + png.message + gotValue(path));
  png.format = PNG_FORMAT_RGBA;
  Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgba.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr))
    throw InputError(path, "(file)",
                     std::string("not a readable PNG image: ") + png.message + gotValue(path));
  return image;
}

ImageComparison compareImages(const Image& expected, const Image& actual, int threshold) {
  if (expected.width != actual.width || expected.height != actual.height)
    throw std::invalid_argument("compareImages: the images differ in size");
  ImageComparison result;
  result.pixels = static_cast<long>(expected.width) * expected.height;
  result.diff = expected;
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x) {
      const std::uint8_t *e = expected.pixel(x, y), *a = actual.pixel(x, y);
      int distance = 0;
      for (int c = 0; c < 3; ++c) distance = std::max(distance, std::abs(int(e[c]) - int(a[c])));
      std::uint8_t* out = result.diff.pixel(x, y);
      if (distance > threshold) {
        ++result.differing;
        out[0] = 230, out[1] = 0, out[2] = 0;
      } else {  // grey in [140, 254]: the reference's shapes still show, none as dark as red
        out[0] = out[1] = out[2] = static_cast<std::uint8_t>(140 + (e[0] + e[1] + e[2]) * 45 / 300);
      }
      out[3] = 255;
    }
  return result;
}

void flipRows(Image& image) {
  const size_t stride = static_cast<size_t>(image.width) * 4;
  for (int y = 0; y < image.height / 2; ++y)
    std::swap_ranges(image.rgba.begin() + y * stride, image.rgba.begin() + (y + 1) * stride,
                     image.rgba.begin() + (image.height - 1 - y) * stride);
}

Image cropped(const Image& image, int x, int y, int w, int h) {
  x = std::clamp(x, 0, image.width);
  y = std::clamp(y, 0, image.height);
  w = std::clamp(w, 0, image.width - x);
  h = std::clamp(h, 0, image.height - y);
  Image out;
  out.width = w;
  out.height = h;
  out.rgba.resize(static_cast<size_t>(w) * h * 4);
  if (w == 0) return out;
  for (int row = 0; row < h; ++row)
    std::copy_n(image.pixel(x, y + row), static_cast<size_t>(w) * 4,
                &out.rgba[static_cast<size_t>(row) * w * 4]);
  return out;
}

}  // namespace cablelab::ui
