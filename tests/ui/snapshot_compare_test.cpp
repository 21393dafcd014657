// `cablelab snapshot --compare REF.png [--tolerance S]`: exit 0 when at most a share S of the
// pixels differ from REF by more than 8 levels in a colour channel, 1 (and F.diff.png) when
// more do, 2 for a bad reference or option; and snapshots repeat byte for byte.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "tests/ui/test_support.h"
#include "ui/image.h"

namespace cablelab::test {
namespace {

namespace fs = std::filesystem;

constexpr int kColourThreshold = 8;  // levels of 255, as documented in docs/cli.md

std::string path(const std::string& name) {
  return (outputDir("compare") / name).string();
}

/// `cablelab snapshot ARGS`.
RunResult snapshot(const std::string& args, const std::string& tag) {
  return run(std::string(CABLELAB_CLI) + " snapshot " + args, "compare_" + tag);
}

/// Writes the snapshot `name` of SCENE_ARGS (fresh: removed first) and returns its path.
std::string reference(const std::string& sceneArgs, const std::string& name) {
  const std::string out = path(name);
  fs::remove(out);
  const RunResult r = snapshot(sceneArgs + " --out " + out, "ref_" + name);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return out;
}

/// Pixels whose largest R, G or B difference exceeds the threshold (the test's own count).
long differing(const ui::Image& a, const ui::Image& b) {
  long n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]));
      n += d > kColourThreshold;
    }
  return n;
}

TEST(SnapshotCompare, TheSameSceneRepeatsByteForByteAndMatchesAtToleranceZero) {
  const std::string first = reference("hand --time 0.5 --size 400x300", "repeat1.png");
  const std::string second = reference("hand --time 0.5 --size 400x300", "repeat2.png");
  const std::string bytes = slurp(first);
  ASSERT_GT(bytes.size(), 1000u);
  EXPECT_TRUE(bytes == slurp(second)) << "two runs of the same snapshot differ in their bytes";

  const std::string out = path("repeat3.png");
  std::ofstream(path("repeat3.diff.png")) << "stale";  // a match removes an old diff
  const RunResult r =
      snapshot("hand --time 0.5 --out " + out + " --compare " + first + " --tolerance 0", "same");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["match"], true);
  EXPECT_EQ(j["differing_pixels"], 0);
  EXPECT_EQ(j["pixels"], 400 * 300);  // the reference's size, with no --size given
  EXPECT_TRUE(j["diff"].is_null());
  EXPECT_FALSE(fs::exists(path("repeat3.diff.png")));
  EXPECT_TRUE(slurp(out) == bytes);
}

TEST(SnapshotCompare, AFallingSceneDiffersAndTheDiffIsRedWhereItDiffers) {
  // The wheel's heavier box falls: at 2 s the boxes and the wheel's spoke have moved.
  const std::string ref = reference("wheel --time 0 --size 480x360", "wheel0.png");
  const std::string out = path("wheel2.png"), diff = path("wheel2.diff.png");
  fs::remove(diff);
  const RunResult r = snapshot("wheel --time 2 --out " + out + " --compare " + ref, "falling");
  ASSERT_EQ(r.exitCode, 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const ui::Image expected = ui::readPng(ref), actual = ui::readPng(out);
  const long n = differing(expected, actual);
  EXPECT_GT(n, 500) << "the boxes moved: many pixels must differ";
  EXPECT_EQ(j["match"], false);
  EXPECT_EQ(j["differing_pixels"], n);
  EXPECT_DOUBLE_EQ(j["share"].get<double>(), static_cast<double>(n) / (480 * 360));
  EXPECT_EQ(j["diff"], diff);
  // One line on stderr naming both files and the diff.
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(out + ": differs from " + ref), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(diff), std::string::npos) << r.err;

  // Red exactly where the pixels differ, grey (the reference, paler) everywhere else.
  const ui::Image shown = ui::readPng(diff);
  ASSERT_EQ(shown.width, 480);
  ASSERT_EQ(shown.height, 360);
  long red = 0, misplaced = 0;
  for (int y = 0; y < shown.height; ++y)
    for (int x = 0; x < shown.width; ++x) {
      const auto* p = shown.pixel(x, y);
      const bool isRed = p[0] == 230 && p[1] == 0 && p[2] == 0;
      const bool isGrey = p[0] == p[1] && p[1] == p[2] && p[0] >= 140;
      int d = 0;
      for (int c = 0; c < 3; ++c)
        d = std::max(d, std::abs(expected.pixel(x, y)[c] - actual.pixel(x, y)[c]));
      red += isRed;
      misplaced += (d > kColourThreshold) ? !isRed : !isGrey;
    }
  EXPECT_EQ(red, n);
  EXPECT_EQ(misplaced, 0);
}

TEST(SnapshotCompare, ToleranceIsTheShareOfPixelsBeyondTheColourThreshold) {
  const std::string out = path("share.png");
  const std::string base = reference("hexagon --time 0.2 --size 320x240", "share_base.png");
  // A reference that differs from the snapshot in exactly 300 pixels by 9 levels in one channel,
  // and in 1000 more by exactly 8 levels (within the threshold, so they do not count).
  ui::Image changed = ui::readPng(base);
  constexpr long kBeyond = 300, kWithin = 1000;
  for (long i = 0; i < kBeyond + kWithin; ++i) {
    const int x = static_cast<int>(i % 320), y = static_cast<int>((i / 320) * 7 % 240);
    std::uint8_t& g = changed.pixel(x, y)[1];
    const int step = i < kBeyond ? 9 : 8;
    g = static_cast<std::uint8_t>(g >= step ? g - step : g + step);
  }
  const std::string ref = path("share_ref.png");
  ui::writePng(changed, ref);
  const double share = static_cast<double>(kBeyond) / (320 * 240);
  auto compare = [&](double tolerance, const std::string& tag) {
    char t[40];
    std::snprintf(t, sizeof t, "%.17g", tolerance);
    return snapshot("hexagon --time 0.2 --out " + out + " --compare " + ref + " --tolerance " + t,
                    tag);
  };
  const RunResult exact = compare(share, "share_exact");
  EXPECT_EQ(exact.exitCode, 0) << exact.err;
  EXPECT_EQ(nlohmann::json::parse(exact.out)["differing_pixels"], kBeyond);
  const RunResult below = compare(share * 0.999, "share_below");
  EXPECT_EQ(below.exitCode, 1) << below.err;
  EXPECT_EQ(nlohmann::json::parse(below.out)["differing_pixels"], kBeyond);
  // The default tolerance is 0.1%: 300 of 76800 pixels (0.39%) is too many.
  const RunResult byDefault =
      snapshot("hexagon --time 0.2 --out " + out + " --compare " + ref, "share_default");
  EXPECT_EQ(byDefault.exitCode, 1) << byDefault.err;
  EXPECT_EQ(nlohmann::json::parse(byDefault.out)["tolerance"], 0.001);
}

TEST(SnapshotCompare, ABadReferenceOrToleranceExitsTwoWithOneLineAndWritesNothing) {
  const std::string ref = reference("hexagon --size 320x200", "bad_ref_base.png");
  const std::string notPng = path("not_a_png.png"), folder = path("a_folder.png");
  std::ofstream(notPng) << "this is text, not an image";
  fs::create_directories(folder);
  const std::string out = path("never.png");
  struct Case {
    std::string args, line;
  };
  const Case cases[] = {
      {"--compare /no/such/ref.png",
       "/no/such/ref.png: (file): cannot open: No such file or directory (got "
       "\"/no/such/ref.png\")"},
      {"--compare " + folder,
       folder + ": (file): is a directory, not a file" + cablelab::gotValue(folder)},
      {"--compare " + ref + " --size 640x480",
       "command line: --size: must be the reference image's size 320x200 (" + ref +
           ") (got \"640x480\")"},
      {"--compare " + ref + " --tolerance 2",
       "command line: --tolerance: must be a number in [0, 1] (got 2)"},
      {"--compare " + ref + " --tolerance -0.1",
       "command line: --tolerance: must be a number in [0, 1] (got -0.1)"},
      {"--tolerance 0.01", "command line: --tolerance: needs --compare REF.png (got 0.01)"},
  };
  for (const Case& c : cases) {
    fs::remove(out);
    const RunResult r = snapshot("hexagon --out " + out + " " + c.args, "bad_ref");
    EXPECT_EQ(r.exitCode, 2) << c.args;
    EXPECT_EQ(r.err, c.line + "\n") << c.args;
    EXPECT_EQ(r.out, "") << c.args;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  fs::remove(out);
  const RunResult text = snapshot("hexagon --out " + out + " --compare " + notPng, "not_png");
  EXPECT_EQ(text.exitCode, 2);
  EXPECT_EQ(text.err.rfind(notPng + ": (file): not a PNG image: ", 0), 0u) << text.err;
  EXPECT_EQ(std::count(text.err.begin(), text.err.end(), '\n'), 1) << text.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace cablelab::test
