#include "ui/image.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/ui/test_support.h"

namespace cablelab::ui {
namespace {

TEST(Image, PngRoundTripAndFlip) {
  Image image{3, 2, std::vector<std::uint8_t>(3 * 2 * 4)};
  for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<std::uint8_t>(i * 10);
  const std::string path = (test::outputDir("image") / "roundtrip.png").string();
  writePng(image, path);
  const Image back = readPng(path);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.rgba, image.rgba);
  Image flipped = image;
  flipRows(flipped);
  EXPECT_EQ(flipped.pixel(0, 0)[0], image.pixel(0, 1)[0]);
}

TEST(Image, ErrorsNameTheFile) {
  try {
    readPng("/nonexistent/dir/x.png");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/x.png"), std::string::npos);
  }
  EXPECT_THROW(writePng(Image{}, test::outputDir("image") / "empty.png"), std::runtime_error);
}

}  // namespace
}  // namespace cablelab::ui
