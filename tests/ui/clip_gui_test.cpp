// The window's clips and demos under Xvfb: the Record button's MP4 against `cablelab record` of
// the same view (ui/recorder.h), and the demos that end starting again inside the view
// (ui/demo_loop.h) at 1280x720 and 1920x1080, with screenshots.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "tests/ui/test_support.h"
#include "ui/clip.h"
#include "ui/gif.h"

namespace cablelab::test {
namespace clip_gui_test {

#define REQUIRE_XVFB_AND_MP4()                                                          \
  if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed: GUI tests skipped"; \
  if (!ui::mp4Available()) GTEST_SKIP() << "built without FFmpeg: no MP4"

std::string xvfb(int width, int height) {
  return "xvfb-run -a -s \"-screen 0 " + std::to_string(width) + "x" + std::to_string(height) +
         "x24\" ";
}

/// Share of pixels of `a` and `b` more than 48 levels apart (H.264 smears one-pixel edges).
double differing(const ui::Image& a, const ui::Image& b, const std::string& diff = {}) {
  return static_cast<double>(countDiffering(a, b, 48, diff)) / (a.width * a.height);
}

TEST(ClipGui, WindowRecordingMatchesTheCliRecordingOfTheSameView) {
  REQUIRE_XVFB_AND_MP4();
  const auto dir = outputDir("clip-gui");
  const std::string window = (dir / "window.mp4").string(), cli = (dir / "cli.mp4").string();
  const RunResult w = run(xvfb(1280, 720) + CABLELAB_CLI +
                              " gui hexagon --size 1280x720 --frames 61 --record " + window,
                          "clip_gui_window");
  const nlohmann::json j = jsonReport(w);
  ASSERT_TRUE(j.contains("record_view")) << w.out;
  const int width = static_cast<int>(j["free"][2].get<double>()) / 2 * 2;
  const int height = static_cast<int>(j["free"][3].get<double>()) / 2 * 2;
  char view[128];
  std::snprintf(view, sizeof view, "%.17g,%.17g,%.17g", j["record_view"][0].get<double>(),
                j["record_view"][1].get<double>(), j["record_view"][2].get<double>());
  // Every step of the same run (60 a second), to find the window's moments among them.
  const RunResult c =
      run(std::string(CABLELAB_CLI) + " record hexagon --time 2.2 --fps 60 --size " +
              std::to_string(width) + "x" + std::to_string(height) + " --view " + view + " --out " +
              cli,
          "clip_gui_cli");
  ASSERT_EQ(c.exitCode, 0) << c.err;
  const ui::DecodedClip a = ui::readClip(window), b = ui::readClip(cli);
  // 60 steps after the first frame at 30 clip frames a second: 30, one either way.
  ASSERT_GE(a.frames.size(), 29u);
  ASSERT_LE(a.frames.size(), 31u);
  EXPECT_EQ(a.frames[0].width, width);
  EXPECT_EQ(a.frames[0].height, height);
  // Frame k of the window is the CLI's frame first + 2 k (one per two steps), and the same
  // picture: the same time stamp, colours, fills and key.
  int first = -1;
  for (int k : {0, 10, 25}) {
    int best = -1;
    double least = 1;
    for (size_t i = 0; i < b.frames.size(); ++i) {
      const double d = differing(a.frames[k], b.frames[i]);
      if (d < least) least = d, best = static_cast<int>(i);
    }
    if (first < 0) first = best - 2 * k;
    EXPECT_EQ(best, first + 2 * k) << "window frame " << k;
    const std::string stem = (dir / ("frame-" + std::to_string(k))).string();
    ui::writePng(a.frames[k], stem + "-window.png");
    ui::writePng(b.frames[best], stem + "-cli.png");
    EXPECT_LT(differing(a.frames[k], b.frames[best], stem + "-diff.png"), 0.01)
        << "window frame " << k << " against CLI frame " << best;
    // Half a second apart is another picture: the match above can fail.
    EXPECT_GT(differing(a.frames[k], b.frames[(best + 30) % b.frames.size()]), 0.02);
  }
  EXPECT_GE(first, 0);
  EXPECT_LE(first, 2);  // the window's clip starts at its first or second step
}

// Issue 38: "in pulley a body reaches its pulley at 2.7 s and the other falls out of view; the
// tackle jams at the top at 3 s with the effort weight off screen; ballast is over in under
// 1 s". Now each starts again when its run ends, and stays in the view throughout.
TEST(ClipGui, DemosThatEndStartAgainInView) {
  if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed: GUI tests skipped";
  for (const auto& [width, height] : {std::pair{1280, 720}, std::pair{1920, 1080}})
    for (const char* scene : {"pulley", "tackle", "ballast"}) {
      const std::string size = std::to_string(width) + "x" + std::to_string(height);
      const std::string shot =
          (outputDir("clip-gui") / (std::string(scene) + "-" + size + ".png")).string();
      // 7 s: past the end of every first run (ballast 2 s, pulley 2.7 s, tackle 3.7 s) and
      // the second after it.
      const RunResult r = run(xvfb(width, height) + CABLELAB_CLI + " gui " + scene + " --size " +
                                  size + " --frames 420 --screenshot " + shot,
                              std::string("demo_") + scene);
      const nlohmann::json j = jsonReport(r);
      std::cout << scene << " " << size << ": " << j.value("restarts", -1) << " restarts, "
                << j.value("frames_out_of_view", -1) << " frames out of view\n";
      EXPECT_GE(j.value("restarts", 0), 1) << scene << " " << size;
      EXPECT_EQ(j.value("frames_out_of_view", -1), 0) << scene << " " << size;
      EXPECT_EQ(ui::readPng(shot).width, width);
    }
}

/// True when every channel of `a` and `b` is within `levels`.
bool nearColour(const std::uint8_t* a, const std::uint8_t* b, int levels) {
  return std::abs(a[0] - b[0]) <= levels && std::abs(a[1] - b[1]) <= levels &&
         std::abs(a[2] - b[2]) <= levels;
}

// Issue 38: the window's GIF of the hexagon turning (1280x720, 4.7 s) was 3.2 MB; a tenth is
// the goal. Its frames are one global palette and only the moving edges, so what is left is how
// many frames a second store them again: 10 (a screen recorder's GIF rate) where 15 made
// 84 kB a simulated second (346 kB for the 4.7 s; 243 kB now). The frames still show the
// hexagon's fill where the hexagon is, as the window drew it.
TEST(ClipGui, WindowGifOfTheTurningHexagonIsSmallAndShowsItsFill) {
  if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed: GUI tests skipped";
  const auto dir = outputDir("clip-gui");
  const std::string gif = (dir / "hexagon.gif").string(), shot = (dir / "hexagon.png").string();
  const RunResult r =
      run(xvfb(1280, 720) + CABLELAB_CLI + " gui hexagon --size 1280x720 --frames 61 --record " +
              gif + " --screenshot " + shot,
          "clip_gui_hexagon_gif");
  const nlohmann::json j = jsonReport(r);
  ASSERT_TRUE(j.contains("record_view")) << r.out;
  const ui::GifAnimation a = ui::readGif(gif);
  ASSERT_GE(a.frames.size(), 9u);
  double seconds = 0;
  for (int delay : a.delays) seconds += delay / 100.0;
  const double bytesPerSecond = std::filesystem::file_size(gif) / seconds;
  std::cout << "hexagon GIF in a 1280x720 window: " << a.frames.size() << " frames, "
            << bytesPerSecond / 1000 << " kB a second\n";
  EXPECT_LT(bytesPerSecond, 68000);  // 59 kB measured, 84 kB at 15 fps
  // The hexagon's fill: the commonest colour within 0.3 m of its axle (the origin) in the
  // window's last frame, not the background; most of that disc shows it in the GIF's last frame.
  const ui::Image window = ui::readPng(shot), &frame = a.frames.back();
  const int left = static_cast<int>(j["free"][0].get<double>()),
            top = static_cast<int>(j["free"][1].get<double>());
  const double cx = j["record_view"][0], cy = j["record_view"][1], mpp = j["record_view"][2];
  const double ax = frame.width / 2.0 - cx / mpp, ay = frame.height / 2.0 + cy / mpp;
  const int radius = static_cast<int>(0.3 / mpp);
  std::vector<std::pair<int, int>> disc;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x)
      if (x * x + y * y <= radius * radius)
        disc.emplace_back(static_cast<int>(ax) + x, static_cast<int>(ay) + y);
  std::map<std::uint32_t, int> counts;
  for (const auto& [x, y] : disc) {
    const std::uint8_t* p = window.pixel(left + x, top + y);
    ++counts[p[0] << 16 | p[1] << 8 | p[2]];
  }
  const auto fill = std::max_element(counts.begin(), counts.end(), [](auto& a, auto& b) {
                      return a.second < b.second;
                    })->first;
  const std::uint8_t fillRgb[3] = {static_cast<std::uint8_t>(fill >> 16),
                                   static_cast<std::uint8_t>(fill >> 8),
                                   static_cast<std::uint8_t>(fill)};
  EXPECT_FALSE(nearColour(fillRgb, frame.pixel(frame.width / 4, frame.height * 3 / 4), 40))
      << "the fill is the background's colour";
  int shown = 0;
  for (const auto& [x, y] : disc) shown += nearColour(frame.pixel(x, y), fillRgb, 8);
  EXPECT_GT(shown, 0.85 * disc.size()) << shown << " of " << disc.size();
  ui::writePng(frame, dir / "hexagon-gif-last.png");
}

}  // namespace clip_gui_test
}  // namespace cablelab::test
