// Offscreen snapshots: determinism, errors, and the golden images of every built-in scene.
// Golden images: tests/golden/<scene>.png, each scene after kGoldenTime at kGoldenWidth x
// kGoldenHeight. At most kMaxDifferingFraction of the pixels may differ by more than
// kLevelTolerance levels. `scripts/update-goldens` rewrites them on purpose
// (CABLELAB_UPDATE_GOLDENS=1); the Golden.* tests are registered per scene in ui_tests_main.cpp.
#include "ui/offscreen.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include "tests/ui/test_support.h"
#include "ui/offscreen_context.h"
#include "ui/scene_catalog.h"

namespace cablelab::ui {

constexpr double kGoldenTime = 0.5;  // s
constexpr int kGoldenWidth = 400, kGoldenHeight = 300;
constexpr int kLevelTolerance = 8;  // of 255
constexpr double kMaxDifferingFraction = 0.005;

void checkGolden(const std::string& scene) {
  const auto world = test::sceneAt(scene, kGoldenTime);
  const Image actual = renderSnapshot(*world, kGoldenWidth, kGoldenHeight);
  const std::string golden = std::string(CABLELAB_SOURCE_DIR) + "/tests/golden/" + scene + ".png";
  if (const char* update = std::getenv("CABLELAB_UPDATE_GOLDENS"); update && *update == '1') {
    writePng(actual, golden);
    std::cout << "wrote " << golden << "\n";
    return;
  }
  if (!std::filesystem::exists(golden))
    FAIL() << "no golden image " << golden << " (run scripts/update-goldens and look at it)";
  const Image expected = readPng(golden);
  ASSERT_EQ(expected.width, actual.width) << golden;
  ASSERT_EQ(expected.height, actual.height) << golden;
  const auto dir = test::outputDir("golden");
  const std::string diff = (dir / (scene + "-diff.png")).string();
  const long differing = test::countDiffering(expected, actual, kLevelTolerance);
  const long allowed = static_cast<long>(kMaxDifferingFraction * actual.width * actual.height);
  if (differing > allowed) {
    test::countDiffering(expected, actual, kLevelTolerance, diff);
    writePng(actual, dir / (scene + "-actual.png"));
    FAIL() << scene << ": " << differing << " pixels differ by more than " << kLevelTolerance
           << " levels (allowed " << allowed << "); diff image: " << diff
           << ", actual: " << (dir / (scene + "-actual.png")).string();
  }
}

namespace {

TEST(Offscreen, SameSceneAndTimeGiveTheSamePixels) {
  for (const SceneEntry& entry : builtinSceneList()) {
    const auto a = test::sceneAt(entry.name, 0.25), b = test::sceneAt(entry.name, 0.25);
    EXPECT_EQ(renderSnapshot(*a, 320, 240).rgba, renderSnapshot(*b, 320, 240).rgba) << entry.name;
  }
}

TEST(Offscreen, SnapshotIsNotBlank) {
  const auto list = builtinSceneList();
  ASSERT_FALSE(list.empty());
  const auto world = test::sceneAt(list.front().name, 0);
  const Image image = renderSnapshot(*world, 200, 150);
  std::set<std::uint32_t> colours;
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    colours.insert(image.rgba[i] << 16 | image.rgba[i + 1] << 8 | image.rgba[i + 2]);
  EXPECT_GT(colours.size(), 20u);
}

TEST(Offscreen, WriteSnapshotPngFailsClearly) {
  const auto list = builtinSceneList();
  ASSERT_FALSE(list.empty());
  const auto world = test::sceneAt(list.front().name, 0);
  try {
    writeSnapshotPng(*world, "/nonexistent/dir/snap.png", 100, 100);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/snap.png"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(writeSnapshotPng(*world, test::outputDir("snap") / "zero.png", 0, 10),
               std::runtime_error);
  const std::string ok = (test::outputDir("snap") / "ok.png").string();
  writeSnapshotPng(*world, ok, 64, 48);
  EXPECT_EQ(readPng(ok).width, 64);
}

TEST(Offscreen, SnapshotTimeAt800x600) {
  // Median of 20 whole snapshots (context, ImGui, render, PNG); printed for the record.
  const auto list = builtinSceneList();
  ASSERT_FALSE(list.empty());
  const std::string scene =
      std::find_if(list.begin(), list.end(),
                   [](const SceneEntry& e) { return e.name == "hexagon"; }) != list.end()
          ? "hexagon"
          : list.front().name;
  const auto world = test::sceneAt(scene, 0.5);
  const std::string path = (test::outputDir("snap") / "timing.png").string();
  std::vector<double> ms, renderMs;
  for (int i = 0; i < 20; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const Image image = renderSnapshot(*world, 800, 600);
    const auto t1 = std::chrono::steady_clock::now();
    writePng(image, path);
    const auto t2 = std::chrono::steady_clock::now();
    renderMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    ms.push_back(std::chrono::duration<double, std::milli>(t2 - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  std::sort(renderMs.begin(), renderMs.end());
  std::cout << "snapshot 800x600 " << scene << ": median " << ms[10] << " ms (render "
            << renderMs[10] << " ms, the rest PNG encoding)\n";
  RecordProperty("snapshot_ms", std::to_string(ms[10]));

  // The frame alone, in a context made once (what a caller rendering many frames pays).
  OffscreenContext context(800, 600);
  const Camera camera = Camera::fit(world->scene().view, 800, 600);
  std::vector<double> frameMs;
  for (int i = 0; i < 20; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    context.render([&](ImDrawList* text) { drawWorld(*world, camera, {}, {}, text); });
    frameMs.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(frameMs.begin(), frameMs.end());
  std::cout << "frame 800x600 in a reused context: median " << frameMs[10] << " ms\n";
  EXPECT_LT(ms[10], 2000.0);
}

}  // namespace
}  // namespace cablelab::ui
