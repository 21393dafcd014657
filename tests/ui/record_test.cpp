// Animated GIFs: the giflib writer round trip (ui/gif.h) and `cablelab record` (headless).
#include <gtest/gtest.h>

#include <gif_lib.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "tests/ui/test_support.h"
#include "ui/gif.h"

namespace cablelab::test {
namespace {

/// A frame of four flat colour bands whose boundary moves with `k`.
ui::Image bands(int width, int height, int k) {
  ui::Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(static_cast<size_t>(width) * height * 4, 255);
  static const std::uint8_t kColours[4][3] = {
      {250, 20, 20}, {20, 200, 40}, {30, 40, 220}, {5, 5, 5}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int band = ((x + 3 * k) / 10 + y / 12) % 4;
      std::copy(kColours[band], kColours[band] + 3, image.pixel(x, y));
    }
  return image;
}

TEST(Gif, WriterRoundTripKeepsFlatColoursAndTheFrameRate) {
  const std::string path = (outputDir("gif") / "bands.gif").string();
  constexpr int kFrames = 12;
  constexpr double kFps = 30;
  {
    ui::GifWriter gif(path, 64, 48, 1 / kFps);
    for (int k = 0; k < kFrames; ++k) gif.add(bands(64, 48, k));
    gif.close();
    EXPECT_EQ(gif.frames(), kFrames);
  }
  const ui::GifAnimation a = ui::readGif(path);
  ASSERT_EQ(a.frames.size(), static_cast<size_t>(kFrames));
  EXPECT_TRUE(a.loops);
  int total = 0;
  for (int d : a.delays) {
    EXPECT_GE(d, 3);  // 3.33 cs per frame, spread as 3s and 4s
    EXPECT_LE(d, 4);
    total += d;
  }
  EXPECT_EQ(total, static_cast<int>(std::lround(kFrames * 100 / kFps)));
  // Four colours fit any palette: every pixel comes back.
  for (int k = 0; k < kFrames; ++k) {
    EXPECT_EQ(countDiffering(a.frames[k], bands(64, 48, k), 7), 0) << "frame " << k;
    EXPECT_GT(countDiffering(a.frames[k], bands(64, 48, k + 1), 7), 100) << "frame " << k;
  }
}

// A still picture with a small square moving over it: each frame after the first stores only
// the rectangle around the square's old and new places, in the one global palette, the
// pixels there that stayed as the transparent index, drawn over the frame before.
TEST(Gif, LaterFramesStoreOnlyWhatChangedWithTheOnePalette) {
  const std::string path = (outputDir("gif") / "square.gif").string();
  auto picture = [](int k) {
    ui::Image image = bands(80, 60, 0);
    for (int y = 20; y < 30; ++y)
      for (int x = 10 + 2 * k; x < 20 + 2 * k; ++x) {
        std::uint8_t* p = image.pixel(x, y);
        p[0] = 240, p[1] = 230, p[2] = 60;
      }
    return image;
  };
  {
    ui::GifWriter gif(path, 80, 60, 0.1);
    for (int k = 0; k < 5; ++k) gif.add(picture(k));
    gif.add(picture(4));  // nothing changed: one transparent pixel
    gif.close();
  }
  int error = 0;
  GifFileType* file = DGifOpenFileName(path.c_str(), &error);
  ASSERT_NE(file, nullptr);
  ASSERT_NE(DGifSlurp(file), GIF_ERROR);
  ASSERT_EQ(file->ImageCount, 6);
  EXPECT_NE(file->SColorMap, nullptr);
  for (int k = 0; k < file->ImageCount; ++k) {
    const SavedImage& image = file->SavedImages[k];
    EXPECT_EQ(image.ImageDesc.ColorMap, nullptr) << "frame " << k << " has its own palette";
    GraphicsControlBlock gcb{};
    DGifSavedExtensionToGCB(file, k, &gcb);
    EXPECT_EQ(gcb.DisposalMode, DISPOSE_DO_NOT);
    if (k == 0 || k == 5) continue;
    // The square moved 2 px right: columns 10 + 2(k-1) .. 19 + 2k, rows 20..29.
    EXPECT_EQ(image.ImageDesc.Left, 10 + 2 * (k - 1)) << k;
    EXPECT_EQ(image.ImageDesc.Width, 12) << k;
    EXPECT_EQ(image.ImageDesc.Top, 20) << k;
    EXPECT_EQ(image.ImageDesc.Height, 10) << k;
    // Inside, the square's middle stayed: transparent.
    ASSERT_GE(gcb.TransparentColor, 0);
    EXPECT_EQ(image.RasterBits[5 * 12 + 5], gcb.TransparentColor) << k;
    EXPECT_NE(image.RasterBits[5 * 12 + 11], gcb.TransparentColor) << k;  // the square's new edge
  }
  EXPECT_EQ(file->SavedImages[5].ImageDesc.Width * file->SavedImages[5].ImageDesc.Height, 1);
  DGifCloseFile(file, &error);
  const ui::GifAnimation a = ui::readGif(path);
  ASSERT_EQ(a.frames.size(), 6u);
  for (int k = 0; k < 6; ++k)
    EXPECT_EQ(countDiffering(a.frames[k], picture(std::min(k, 4)), 7), 0) << "frame " << k;
}

// A colour that drifts by a few levels (a cable's tension colour from one frame to the next) is
// left as shown: the frame stores nothing for it; a visible change is written. Both colours are
// in the first frame, so the palette holds each exactly.
TEST(Gif, SmallColourDriftIsLeftVisibleChangesAreWritten) {
  const std::string path = (outputDir("gif") / "drift.gif").string();
  auto picture = [](int left) {  // three grey strips: `left`, 106 and 140
    ui::Image image;
    image.width = 39;
    image.height = 10;
    image.rgba.assign(39 * 10 * 4, 255);
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 39; ++x) {
        std::uint8_t* p = image.pixel(x, y);
        p[0] = p[1] = p[2] = static_cast<std::uint8_t>(x < 13 ? left : x < 26 ? 106 : 140);
      }
    return image;
  };
  {
    ui::GifWriter gif(path, 39, 10, 0.1);
    gif.add(picture(100));
    gif.add(picture(106));  // 6 levels: left as it was
    gif.add(picture(140));  // 40 levels: written
    gif.close();
  }
  int error = 0;
  GifFileType* file = DGifOpenFileName(path.c_str(), &error);
  ASSERT_NE(file, nullptr);
  ASSERT_NE(DGifSlurp(file), GIF_ERROR);
  ASSERT_EQ(file->ImageCount, 3);
  // 127 colours and the transparent one: LZW codes from 8 bits.
  EXPECT_EQ(file->SColorMap->ColorCount, 128);
  const GifImageDesc& still = file->SavedImages[1].ImageDesc;
  EXPECT_EQ(still.Width * still.Height, 1);  // nothing to write
  const GifImageDesc& changed = file->SavedImages[2].ImageDesc;
  EXPECT_EQ(changed.Left, 0);
  EXPECT_EQ(changed.Width, 13);
  EXPECT_EQ(changed.Height, 10);
  DGifCloseFile(file, &error);
  const ui::GifAnimation a = ui::readGif(path);
  ASSERT_EQ(a.frames.size(), 3u);
  EXPECT_EQ(a.frames[1].pixel(5, 5)[0], 100);  // shown 6 levels off the render
  EXPECT_EQ(a.frames[2].pixel(5, 5)[0], 140);
  EXPECT_EQ(a.frames[2].pixel(20, 5)[0], 106);
}

// A scene at rest in its first frame shows its cables' tension colours from the second on: the
// palette is chosen from both, so they come back exactly (with the first frame's palette alone,
// the red below would be drawn grey).
TEST(Gif, ThePaletteHasTheSecondFramesColoursToo) {
  const std::string path = (outputDir("gif") / "second.gif").string();
  ui::Image grey = bands(32, 16, 0);
  for (size_t i = 0; i < grey.rgba.size(); i += 4)
    grey.rgba[i] = grey.rgba[i + 1] = grey.rgba[i + 2] = 100;
  ui::Image red = grey;
  for (int x = 0; x < 16; ++x)
    for (int y = 0; y < 16; ++y) {
      std::uint8_t* p = red.pixel(x, y);
      p[0] = 200, p[1] = 30, p[2] = 30;
    }
  {
    ui::GifWriter gif(path, 32, 16, 0.1);
    gif.add(grey);
    EXPECT_EQ(gif.frames(), 1);  // counted, held for the palette
    gif.add(red);
    gif.add(grey);
    gif.close();
    EXPECT_EQ(gif.frames(), 3);
  }
  const ui::GifAnimation a = ui::readGif(path);
  ASSERT_EQ(a.frames.size(), 3u);
  EXPECT_EQ(countDiffering(a.frames[0], grey, 0), 0);
  EXPECT_EQ(countDiffering(a.frames[1], red, 0), 0);
  EXPECT_EQ(countDiffering(a.frames[2], grey, 0), 0);
  // One frame only: still written, at close.
  const std::string one = (outputDir("gif") / "one.gif").string();
  {
    ui::GifWriter gif(one, 32, 16, 0.1);
    gif.add(red);
    gif.close();
  }
  const ui::GifAnimation b = ui::readGif(one);
  ASSERT_EQ(b.frames.size(), 1u);
  EXPECT_EQ(countDiffering(b.frames[0], red, 0), 0);
}

TEST(Gif, WriterRejectsAWrongSizeAndAnUnwritablePath) {
  EXPECT_THROW(ui::GifWriter("/nonexistent/dir/x.gif", 10, 10, 0.1), std::runtime_error);
  ui::GifWriter gif((outputDir("gif") / "size.gif").string(), 10, 10, 0.1);
  EXPECT_THROW(gif.add(bands(11, 10, 0)), std::runtime_error);
  gif.close();  // no frame: still a GIF file (a header without images)
  std::ifstream file(outputDir("gif") / "size.gif", std::ios::binary);
  std::string head(6, ' ');
  file.read(head.data(), 6);
  EXPECT_EQ(head, "GIF89a");
}

TEST(RecordCli, HexagonForTwoSecondsHasSixtyDifferentFrames) {
  const std::string out = (outputDir("record") / "clip.gif").string();
  const RunResult r =
      run(std::string(CABLELAB_CLI) + " record hexagon --out " + out + " --time 2 --size 320x240",
          "record_hexagon");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ui::GifAnimation a = ui::readGif(out);
  // One frame per 1/30 s from t = 0 to t = 2 inclusive.
  ASSERT_EQ(a.frames.size(), 61u);
  EXPECT_EQ(a.frames[0].width, 320);
  EXPECT_EQ(a.frames[0].height, 240);
  // The hexagon spins and the weight swings: every frame differs from the one before.
  for (size_t k = 1; k < a.frames.size(); ++k)
    EXPECT_GT(countDiffering(a.frames[k], a.frames[k - 1], 40), 20) << "frame " << k;
  // Frames to look at.
  ui::writePng(a.frames[0], outputDir("record") / "clip-0.png");
  ui::writePng(a.frames[45], outputDir("record") / "clip-45.png");
  int delaySum = 0;
  for (int d : a.delays) delaySum += d;
  EXPECT_EQ(delaySum, 203);  // round(61 * 100 / 30)
}

TEST(RecordCli, BadArgumentsExitTwoWithOneLine) {
  const std::string out = (outputDir("record") / "bad.gif").string();
  const std::string o = " --out " + out;
  const std::vector<std::string> bad = {"hexagon" + o + " --fps 0 --time 0.1",
                                        "hexagon" + o + " --fps 200 --time 0.1",
                                        "hexagon" + o + " --time -1",
                                        "hexagon" + o + " --size 10 --time 0.1",
                                        "hexagon" + o + " --size 0x100 --time 0.1",
                                        "nosuchscene" + o,
                                        "hexagon --out /nonexistent/dir/clip.gif",
                                        "hexagon" + o + " --set nosuch=1",
                                        "hexagon" + o + " --fps abc",
                                        "hexagon --time 0.1"};
  for (const std::string& args : bad) {
    const RunResult r = run(std::string(CABLELAB_CLI) + " record " + args, "record_bad");
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  EXPECT_EQ(run(std::string(CABLELAB_CLI) + " record --help", "record_help").exitCode, 0);
}

}  // namespace
}  // namespace cablelab::test
