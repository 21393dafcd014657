// Clips (ui/clip.h): the MP4 writer decoded back with FFmpeg, `cablelab record --out F.mp4`
// against offscreen renders of the same moments, the GIF palette that keeps light fills, and the
// sizes of GIF and MP4 clips against the GIFs `record` wrote before.
#include <gtest/gtest.h>

#include <gif_lib.h>

#include <filesystem>
#include <map>
#include <utility>

#include "engine/scenes/scene_registry.h"
#include "tests/ui/test_support.h"
#include "ui/camera.h"
#include "ui/clip.h"
#include "ui/gif.h"
#include "ui/gif_palette.h"
#include "ui/offscreen.h"
#include "ui/recorder.h"
#include "ui/tension_scale.h"

namespace cablelab::test {
namespace clip_test {

// H.264 at CRF 23 in 4:2:0 moves flat colours by a few levels and smears the one-pixel edges of
// thin coloured lines and text: a pixel counts as different beyond kVideoLevels of 255, and a
// frame matches a render when at most kVideoShare of its pixels do.
constexpr int kVideoLevels = 48;
constexpr double kVideoShare = 0.01;

/// Flat colour bands whose boundary moves with `k` (a frame a codec cannot mistake for another).
ui::Image movingBands(int width, int height, int k) {
  ui::Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(static_cast<size_t>(width) * height * 4, 255);
  static const std::uint8_t kColours[4][3] = {
      {250, 20, 20}, {20, 200, 40}, {30, 40, 220}, {245, 245, 240}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int band = ((x + 4 * k) / 16 + y / 16) % 4;
      std::copy(kColours[band], kColours[band] + 3, image.pixel(x, y));
    }
  return image;
}

/// The frame `cablelab record` draws of `world` at its time: its camera, colour scale and notes.
ui::Image recordedLook(const World& world, const std::string& name, int width, int height) {
  ui::RenderOptions options;
  options.tensionScale = ui::loadTensionScale(world.scene());
  options.markerLegend = true;
  ui::Overlay overlay;
  overlay.notes = ui::clipNotes(world, name);
  return ui::renderSnapshot(world, ui::Camera::fit(world.scene().view, width, height), overlay,
                            options);
}

double share(const ui::Image& a, const ui::Image& b, int levels, const std::string& diff = {}) {
  return static_cast<double>(countDiffering(a, b, levels, diff)) / (a.width * a.height);
}

#define REQUIRE_MP4() \
  if (!ui::mp4Available()) GTEST_SKIP() << "built without FFmpeg: no MP4"

TEST(Clip, TheExtensionPicksTheFormat) {
  EXPECT_EQ(ui::clipFormatFor("a/b.mp4"), ui::ClipFormat::Mp4);
  EXPECT_EQ(ui::clipFormatFor("B.MP4"), ui::ClipFormat::Mp4);
  EXPECT_EQ(ui::clipFormatFor("b.gif"), ui::ClipFormat::Gif);
  EXPECT_EQ(ui::clipFormatFor("b.mp4.gif"), ui::ClipFormat::Gif);
  EXPECT_EQ(ui::clipFormatFor("clip"), ui::ClipFormat::Gif);  // as `record` always wrote
  int w = 671, h = 677;
  ui::clipSize(ui::ClipFormat::Mp4, w, h);
  EXPECT_EQ(w, 670);
  EXPECT_EQ(h, 676);
  ui::clipSize(ui::ClipFormat::Gif, w = 671, h = 677);
  EXPECT_EQ(w, 671);
}

// A demo that starts again (or a reset) sends the simulated clock back: the clip goes on.
TEST(Recorder, GoesOnRecordingWhenTheClockGoesBack) {
  ui::Recorder recorder;
  recorder.start((outputDir("clip") / "restart.gif").string(), 32, 16, 10, 0);
  int added = 0;
  for (double t : {0.0, 0.05, 0.1, 0.2, 0.3, 0.0, 0.05, 0.1, 0.2}) {
    recorder.follow(t);
    if (recorder.due(t)) recorder.add(movingBands(32, 16, added++), t);
  }
  EXPECT_EQ(added, 7);  // 0, 0.1, 0.2, 0.3, then 0, 0.1, 0.2 again
  EXPECT_FALSE(recorder.stop().empty());
  EXPECT_FALSE(recorder.failed());
  EXPECT_EQ(ui::readGif((outputDir("clip") / "restart.gif").string()).frames.size(), 7u);
}

TEST(Mp4, WriterRoundTripKeepsEveryFrameItsSizeAndItsTime) {
  REQUIRE_MP4();
  const std::string path = (outputDir("clip") / "bands.mp4").string();
  constexpr int kFrames = 40, kWidth = 96, kHeight = 64;
  constexpr double kFps = 25;
  {
    auto mp4 = ui::openClip(path, kWidth, kHeight, 1 / kFps);
    for (int k = 0; k < kFrames; ++k) mp4->add(movingBands(kWidth, kHeight, k));
    mp4->close();
    EXPECT_EQ(mp4->frames(), kFrames);
  }
  const ui::DecodedClip clip = ui::readClip(path);
  ASSERT_EQ(clip.frames.size(), static_cast<size_t>(kFrames));
  for (int k = 0; k < kFrames; ++k) {
    ASSERT_EQ(clip.frames[k].width, kWidth);
    ASSERT_EQ(clip.frames[k].height, kHeight);
    EXPECT_NEAR(clip.times[k], k / kFps, 1e-6) << "frame " << k;
    // Frame k is band picture k, not its neighbour (4 px apart).
    EXPECT_LT(share(clip.frames[k], movingBands(kWidth, kHeight, k), kVideoLevels), 0.03) << k;
    EXPECT_GT(share(clip.frames[k], movingBands(kWidth, kHeight, k + 1), kVideoLevels), 0.1) << k;
  }
  ui::writePng(clip.frames[20], outputDir("clip") / "bands-20.png");
}

TEST(Mp4, OddSidesAndUnwritablePathsAreRefused) {
  REQUIRE_MP4();
  EXPECT_THROW(ui::openClip((outputDir("clip") / "odd.mp4").string(), 95, 64, 0.04),
               std::runtime_error);
  EXPECT_THROW(ui::openClip("/nonexistent/dir/x.mp4", 96, 64, 0.04), std::runtime_error);
}

TEST(RecordCli, Mp4OfHexagonMatchesOffscreenRendersAtItsFramesTimes) {
  REQUIRE_MP4();
  const std::string out = (outputDir("clip") / "hexagon.mp4").string();
  const RunResult r =
      run(std::string(CABLELAB_CLI) + " record hexagon --out " + out + " --time 2 --size 320x240",
          "record_hexagon_mp4");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ui::DecodedClip clip = ui::readClip(out);
  ASSERT_EQ(clip.frames.size(), 61u);  // t = 0, 1/30, ..., 2 s
  EXPECT_EQ(clip.frames[0].width, 320);
  EXPECT_EQ(clip.frames[0].height, 240);
  EXPECT_NEAR(clip.times[60], 2.0, 1e-6);
  for (int k : {0, 15, 45, 60}) {
    const auto world = sceneAt("hexagon", k / 30.0);
    const ui::Image expected = recordedLook(*world, "hexagon", 320, 240);
    const std::string stem = (outputDir("clip") / ("hexagon-" + std::to_string(k))).string();
    ui::writePng(clip.frames[k], stem + ".png");
    EXPECT_LT(share(clip.frames[k], expected, kVideoLevels, stem + "-diff.png"), kVideoShare)
        << "frame " << k << " against the render at " << k / 30.0 << " s";
    // A third of a second earlier is visibly another picture (the check can fail).
    if (k >= 15) {
      const auto before = sceneAt("hexagon", (k - 10) / 30.0);
      EXPECT_GT(share(clip.frames[k], recordedLook(*before, "hexagon", 320, 240), kVideoLevels),
                2 * kVideoShare)
          << "frame " << k;
    }
  }
}

// The GIFs `record` wrote before they had one palette and transparent unchanged pixels: 4.7 s
// at 1280x720, in bytes (issue 38).
constexpr double kOldGifBytesHexagon = 2115987, kOldGifBytesPulley = 1572082;

/// The number of frames of a GIF and whether all of them draw with its one global palette.
std::pair<int, bool> gifFramesAndOnePalette(const std::string& path) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  if (!gif || DGifSlurp(gif) == GIF_ERROR) return {-1, false};
  bool one = gif->SColorMap != nullptr;
  for (int k = 0; k < gif->ImageCount; ++k) one = one && !gif->SavedImages[k].ImageDesc.ColorMap;
  const int frames = gif->ImageCount;
  DGifCloseFile(gif, &error);
  return {frames, one};
}

TEST(RecordCli, ClipsAreAFractionOfTheOldGifs) {
  const auto dir = outputDir("clip");
  // GIFs at 15 fps (the window's GIF rate before it was 10), MP4 at the window's 30.
  auto record = [&](const std::string& scene, const std::string& name) {
    const std::string fps = ui::clipFormatFor(name) == ui::ClipFormat::Gif ? "15" : "30";
    const RunResult r = run(std::string(CABLELAB_CLI) + " record " + scene + " --time 4.7 " +
                                "--fps " + fps + " --size 1280x720 --out " + (dir / name).string(),
                            "record_" + name);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return static_cast<double>(std::filesystem::file_size(dir / name));
  };
  const double pulley = record("pulley", "pulley-720.gif");
  const double hexagon = record("hexagon", "hexagon-720.gif");
  std::cout << "4.7 s at 1280x720: pulley GIF " << pulley << " bytes ("
            << pulley / kOldGifBytesPulley << " of the old), hexagon GIF " << hexagon << " ("
            << hexagon / kOldGifBytesHexagon << ")\n";
  // The pulley rests between its drops: what changed is little (0.07 of the old). The hexagon
  // turns and its weight swings in every frame: some 6,000 pixels of moving edges a frame
  // (0.20 of the old).
  EXPECT_LE(10 * pulley, kOldGifBytesPulley);
  EXPECT_LE(4.5 * hexagon, kOldGifBytesHexagon);
  for (const char* name : {"pulley-720.gif", "hexagon-720.gif"})  // 4.7 x 15 + 1
    EXPECT_EQ(gifFramesAndOnePalette((dir / name).string()), std::make_pair(71, true)) << name;
  if (!ui::mp4Available()) return;
  const double mp4 = record("pulley", "pulley-720.mp4");
  std::cout << "pulley MP4 " << mp4 << " bytes\n";
  EXPECT_LE(10 * mp4, kOldGifBytesPulley);
  EXPECT_EQ(ui::readClip((dir / "pulley-720.mp4").string()).frames.size(), 142u);  // 4.7 x 30 + 1
}

/// The pixels of `actual` more than `levels` off `expected` (in any channel) where `expected`
/// is flat: the pixel and its four neighbours within `levels` of each other (not an edge).
long insideDiffering(const ui::Image& actual, const ui::Image& expected, int levels) {
  auto off = [&](const std::uint8_t* a, const std::uint8_t* b) {
    return std::abs(a[0] - b[0]) > levels || std::abs(a[1] - b[1]) > levels ||
           std::abs(a[2] - b[2]) > levels;
  };
  long count = 0;
  for (int y = 1; y + 1 < expected.height; ++y)
    for (int x = 1; x + 1 < expected.width; ++x) {
      const std::uint8_t* e = expected.pixel(x, y);
      const bool flat = !off(e, expected.pixel(x - 1, y)) && !off(e, expected.pixel(x + 1, y)) &&
                        !off(e, expected.pixel(x, y - 1)) && !off(e, expected.pixel(x, y + 1));
      if (flat && off(actual.pixel(x, y), e)) ++count;
    }
  return count;
}

// Every built-in scene for 2 s at 640x360 as the window records a GIF (15 fps): its size against
// the GIF the old writer (a palette per frame, the changed rectangle, no transparency) made of
// the same renders at 30 fps, in bytes; and its last frame against the render at 2 s.
const std::map<std::string, double> kOldGifBytes640x360x2s = {
    {"ballast", 182443}, {"capstan", 62024},   {"hand", 298387},
    {"hexagon", 316010}, {"membrane", 221470}, {"pulley", 315045},
    {"tackle", 344407},  {"wheel", 214793},    {"winch", 214104}};

TEST(RecordCli, GifOfEveryBuiltinSceneIsSmallAndMatchesTheRender) {
  const auto dir = outputDir("clip");
  double sumOfRatios = 0;
  for (const SceneInfo& scene : builtinScenes()) {
    const std::string& name = scene.name;
    ASSERT_TRUE(kOldGifBytes640x360x2s.count(name)) << name << ": no old size measured";
    const std::string out = (dir / (name + "-360.gif")).string();
    const RunResult r = run(std::string(CABLELAB_CLI) + " record " + name +
                                " --time 2 --fps 15 --size 640x360 --out " + out,
                            "record_" + name + "_360");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const double ratio = std::filesystem::file_size(out) / kOldGifBytes640x360x2s.at(name);
    std::cout << name << ": " << std::filesystem::file_size(out) << " bytes, " << ratio
              << " of the old\n";
    EXPECT_LT(ratio, 0.3) << name;
    sumOfRatios += ratio;
    // The last frame (t = 2 s): the render to a few levels, light fills and time stamp included.
    const ui::GifAnimation gif = ui::readGif(out);
    ASSERT_EQ(gif.frames.size(), 31u) << name;
    const auto world = sceneAt(name, 2.0);
    const std::string stem = (dir / (name + "-360-last")).string();
    ui::writePng(gif.frames.back(), stem + ".png");
    const ui::Image expected = recordedLook(*world, name, 640, 360);
    // Anti-aliased edges of colours the first frame lacked come back to a few tens of levels;
    // the flat insides (fills, background) to 24 levels everywhere: no fill is lost.
    EXPECT_LT(share(gif.frames.back(), expected, 24, stem + "-diff.png"), 0.006) << name;
    EXPECT_LT(insideDiffering(gif.frames.back(), expected, 24), 20) << name;
  }
  EXPECT_LT(sumOfRatios / builtinScenes().size(), 0.21);  // 0.19 measured
}

TEST(RecordCli, GifFramesKeepTheLightFillsOfTheRender) {
  // The weight's light fill and the background survive the palette: the GIF's frames are the
  // renders to a few levels (a median cut merged the fill into the background), also where a
  // frame is drawn over the ones before it (transparent pixels) and its tension colours were
  // not in the first frame's palette.
  const std::string out = (outputDir("clip") / "hexagon.gif").string();
  const RunResult r =
      run(std::string(CABLELAB_CLI) + " record hexagon --out " + out + " --time 1 --size 320x240",
          "record_hexagon_gif");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ui::GifAnimation gif = ui::readGif(out);
  ASSERT_EQ(gif.frames.size(), 31u);
  for (int k : {0, 10, 20, 30}) {
    const auto world = sceneAt("hexagon", k / 30.0);
    const ui::Image expected = recordedLook(*world, "hexagon", 320, 240);
    ui::writePng(gif.frames[k], outputDir("clip") / ("hexagon-gif-" + std::to_string(k) + ".png"));
    EXPECT_LT(share(gif.frames[k], expected, 12), 0.005) << "frame " << k;
  }
}

TEST(GifPalette, KeepsFlatColoursExactlyAndCoversRareOnes) {
  // 300 flat colours, column x in colour x: columns 0..249 twenty pixels each, 250..299 one
  // pixel each (the rest of their column colour 0), and one far colour in a single pixel.
  ui::Image image;
  image.width = 300;
  image.height = 20;
  image.rgba.assign(300 * 20 * 4, 255);
  auto colour = [](int c, std::uint8_t* p) {
    p[0] = static_cast<std::uint8_t>(8 * (c % 25) + 3);
    p[1] = static_cast<std::uint8_t>(8 * (c / 25) + 3);
    p[2] = 100;
  };
  for (int x = 0; x < 300; ++x)
    for (int y = 0; y < 20; ++y) colour(x < 250 || y == 0 ? x : 0, image.pixel(x, y));
  const std::uint8_t far[3] = {250, 250, 250};
  std::copy(far, far + 3, image.pixel(299, 19));
  ui::GifPalette palette(image, 255);
  ASSERT_EQ(palette.colours().size(), 255u);
  for (int x = 0; x < 250; ++x) {  // the common colours come back exactly
    const auto& c = palette.colours()[palette.indexOf(image.pixel(x, 5))];
    EXPECT_EQ(c[0], image.pixel(x, 5)[0]) << x;
    EXPECT_EQ(c[1], image.pixel(x, 5)[1]) << x;
    EXPECT_EQ(c[2], 100) << x;
  }
  // The one far pixel has its own entry (ranking by count alone drops it for a grey near it).
  const auto& f = palette.colours()[palette.indexOf(far)];
  EXPECT_EQ(std::vector<int>(f.begin(), f.end()), std::vector<int>({250, 250, 250}));
  for (int x = 250; x < 300; ++x) {  // the rare ones: at most two steps of 8 levels away
    const auto& c = palette.colours()[palette.indexOf(image.pixel(x, 0))];
    EXPECT_LE(std::abs(c[0] - image.pixel(x, 0)[0]) + std::abs(c[1] - image.pixel(x, 0)[1]), 16)
        << x;
  }
  // A colour the image lacks: the nearest entry.
  const std::uint8_t pink[3] = {240, 200, 200};
  const auto& n = palette.colours()[palette.indexOf(pink)];
  EXPECT_EQ(std::vector<int>(n.begin(), n.end()), std::vector<int>({250, 250, 250}));
}

TEST(RecordCli, Mp4ArgumentsAreCheckedWithOneLine) {
  const std::string out = (outputDir("clip") / "bad.mp4").string();
  std::vector<std::string> bad = {"hexagon --out " + out + " --fps 121 --time 0.1",
                                  "hexagon --out " + out + " --view 1,2 --time 0.1",
                                  "hexagon --out " + out + " --view 0,0,-1 --time 0.1",
                                  "hexagon --out /nonexistent/dir/clip.mp4 --time 0.1"};
  if (ui::mp4Available()) bad.push_back("hexagon --out " + out + " --size 321x240 --time 0.1");
  for (const std::string& args : bad) {
    const RunResult r = run(std::string(CABLELAB_CLI) + " record " + args, "record_bad_mp4");
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("command line: ", 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  if (!ui::mp4Available()) {  // says why, and what to do
    const RunResult r =
        run(std::string(CABLELAB_CLI) + " record hexagon --time 0.1 --out " + out, "record_nomp4");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("FFmpeg"), std::string::npos) << r.err;
  }
}

}  // namespace clip_test
}  // namespace cablelab::test
