// Tests for `cablelab fit` (app/cmd_fit.cpp) through the real executable: the JSON contract,
// --generate, --plots, and exit 2 with one line naming file, row and field for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "tests/support/engine_test_support.h"

#ifdef CABLELAB_HAVE_OFFSCREEN
#include "ui/image.h"
#endif

namespace {

namespace fs = std::filesystem;

const std::string kPulleys = "--pulleys -0.2,0,0.2,0";

using CliRun = cablelab::test::CommandResult;

std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A fresh directory per test under the system temp dir.
fs::path fitScratch() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::temp_directory_path() /
                 ("cablelab_fit_cli_" + std::to_string(getpid()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// `cablelab fit ARGS`, run from the source directory so data paths can be relative.
cablelab::test::CommandResult cablelab(const std::string& args) {
  return cablelab::test::runCli("fit " + args, CABLELAB_SOURCE_DIR);
}

TEST(FitCli, FitsTheExampleDataAndPrintsOneJsonObject) {
  const CliRun run = cablelab("assets/data/membrane_example.csv " + kPulleys);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const auto j = nlohmann::json::parse(run.out);
  for (const char* key : {"k", "preload", "rms_fy", "rms_angle_deg", "k_stderr", "preload_stderr",
                          "iterations", "rows"})
    EXPECT_TRUE(j.contains(key)) << key;
  // The example was generated with k = 25 N/m, preload = 0.8 m (membrane_example.json).
  const auto truth = nlohmann::json::parse(
      readFile(fs::path(CABLELAB_SOURCE_DIR) / "assets/data/membrane_example.json"));
  EXPECT_NEAR(j["k"].get<double>(), truth["k"].get<double>(), 0.02 * 25.0);
  EXPECT_NEAR(j["preload"].get<double>(), truth["preload"].get<double>(), 0.02 * 0.8);
  EXPECT_NEAR(j["rms_fy"].get<double>(), 0.05, 0.01);
  EXPECT_NEAR(j["rms_angle_deg"].get<double>(), 1.0, 0.2);
  EXPECT_EQ(j["rows"].get<int>(), 192);
  EXPECT_GT(j["k_stderr"].get<double>(), 0.0);
  // Full double precision: more than the 6 significant digits of a default stream.
  const std::string k = run.out.substr(run.out.find("\"k\":") + 4);
  EXPECT_GT(k.find(','), 10u) << run.out;
}

TEST(FitCli, GenerateThenFitRecoversTheParametersAndIsReproducible) {
  const fs::path dir = fitScratch();
  const std::string data = (dir / "gen.csv").string();
  const CliRun gen = cablelab("--generate " + data +
                              " --pulleys 0,0,0.5,0 --k 40 --preload 0.5 --noise-fy 0 "
                              "--noise-angle-deg 0 --seed 9 --grid 6x5 --depth -0.1,-0.3");
  ASSERT_EQ(gen.exitCode, 0) << gen.err;
  const auto info = nlohmann::json::parse(gen.out);
  EXPECT_EQ(info["rows"].get<int>(), 30);
  EXPECT_EQ(info["k"].get<double>(), 40.0);
  const CliRun fit = cablelab(data + " --pulleys 0,0,0.5,0");
  ASSERT_EQ(fit.exitCode, 0) << fit.err;
  const auto j = nlohmann::json::parse(fit.out);
  EXPECT_NEAR(j["k"].get<double>(), 40.0, 1e-8 * 40.0);
  EXPECT_NEAR(j["preload"].get<double>(), 0.5, 1e-8 * 0.5);
  // The shipped example is exactly what its recorded command produces.
  const std::string again = (dir / "example.csv").string();
  const CliRun example =
      cablelab("--generate " + again + " " + kPulleys + " --k 25 --preload 0.8 --seed 2024");
  ASSERT_EQ(example.exitCode, 0) << example.err;
  EXPECT_EQ(readFile(again),
            readFile(fs::path(CABLELAB_SOURCE_DIR) / "assets/data/membrane_example.csv"));
  fs::remove_all(dir);
}

TEST(FitCli, PlotsWritesQuiverAndScatterData) {
  const fs::path dir = fitScratch() / "plots";
  const CliRun run =
      cablelab("assets/data/membrane_example.csv " + kPulleys + " --plots " + dir.string());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string quiver = readFile(dir / "quiver.csv");
  const std::string scatter = readFile(dir / "scatter.csv");
  EXPECT_EQ(quiver.rfind("x,y,measured_angle_deg,model_angle_deg,", 0), 0u);
  EXPECT_EQ(scatter.rfind("measured_fy,model_fy\n", 0), 0u);
  EXPECT_EQ(std::count(quiver.begin(), quiver.end(), '\n'), 193);
  EXPECT_EQ(std::count(scatter.begin(), scatter.end(), '\n'), 193);
  fs::remove_all(dir.parent_path());
}

#ifdef CABLELAB_HAVE_OFFSCREEN
/// Pixels whose channels differ by more than 60 levels: data colours, not white, grey or black.
long colouredPixels(const cablelab::ui::Image& image) {
  long n = 0;
  for (size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
    const int lo = std::min({image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]});
    const int hi = std::max({image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]});
    n += hi - lo > 60;
  }
  return n;
}

TEST(FitCli, PlotsWritesNonBlankPngsOfTheRequestedSize) {
  const fs::path dir = fitScratch() / "png";
  const CliRun run = cablelab("assets/data/membrane_example.csv " + kPulleys + " --plots " +
                              dir.string() + " --plot-size 640x480");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  for (const char* name : {"quiver", "scatter"}) {
    const fs::path png = dir / (std::string(name) + ".png");
    ASSERT_TRUE(fs::exists(png)) << png;
    EXPECT_NE(run.out.find(png.string()), std::string::npos) << run.out;
    const cablelab::ui::Image image = cablelab::ui::readPng(png.string());
    EXPECT_EQ(image.width, 640) << name;
    EXPECT_EQ(image.height, 480) << name;
    std::set<std::uint32_t> colours;
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4)
      colours.insert(image.rgba[i] << 16 | image.rgba[i + 1] << 8 | image.rgba[i + 2]);
    EXPECT_GT(colours.size(), 20u) << name << " looks blank";
    // 192 measurements: hundreds of red, cyan or blue pixels at least.
    EXPECT_GT(colouredPixels(image), 1000) << name;
  }
  // Default size 800x600.
  const fs::path defaults = dir.parent_path() / "default";
  ASSERT_EQ(
      cablelab("assets/data/membrane_example.csv " + kPulleys + " --plots " + defaults.string())
          .exitCode,
      0);
  EXPECT_EQ(cablelab::ui::readPng((defaults / "scatter.png").string()).width, 800);
  EXPECT_EQ(cablelab::ui::readPng((defaults / "quiver.png").string()).height, 600);
  // A bad size is an input error naming the flag.
  const CliRun bad = cablelab("assets/data/membrane_example.csv " + kPulleys + " --plots " +
                              dir.string() + " --plot-size 10x10");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--plot-size"), std::string::npos) << bad.err;
  fs::remove_all(dir.parent_path());
}
#endif

TEST(FitCli, HelpExitsZero) {
  const CliRun run = cablelab("--help");
  EXPECT_EQ(run.exitCode, 0);
  EXPECT_NE(run.out.find("--pulleys"), std::string::npos);
  EXPECT_NE(run.out.find("--generate"), std::string::npos);
}

/// Exit 2, one line on stderr containing `expected` (file, field, what), nothing on stdout.
void expectInputError(const std::string& args, const std::string& expected) {
  const CliRun run = cablelab(args);
  EXPECT_EQ(run.exitCode, 2) << args;
  EXPECT_EQ(run.out, "") << args;
  EXPECT_NE(run.err.find(expected), std::string::npos) << "stderr: " << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

TEST(FitCli, BadDataFilesExitTwoNamingRowAndField) {
  expectInputError("tests/data/bad/fit_missing_column.csv " + kPulleys,
                   "tests/data/bad/fit_missing_column.csv: header: missing column \"angle_deg\"");
  expectInputError("tests/data/bad/fit_two_rows.csv " + kPulleys,
                   "tests/data/bad/fit_two_rows.csv: rows: need at least 3 measurements");
  expectInputError("tests/data/bad/fit_nan.csv " + kPulleys,
                   "tests/data/bad/fit_nan.csv: row 7, fy: must be a finite number (got \"nan\")");
  expectInputError(
      "tests/data/bad/fit_not_a_number.csv " + kPulleys,
      "tests/data/bad/fit_not_a_number.csv: row 2, angle_deg: must be a finite number");
  expectInputError("tests/data/bad/fit_on_line.csv " + kPulleys,
                   "tests/data/bad/fit_on_line.csv: row 3, y: point lies on the band between the "
                   "pulleys");
  expectInputError(
      "tests/data/bad/does_not_exist.csv " + kPulleys,
      "tests/data/bad/does_not_exist.csv: (file): cannot open: No such file or directory (got "
      "\"tests/data/bad/does_not_exist.csv\")");
}

TEST(FitCli, BadPulleysExitTwo) {
  expectInputError("assets/data/membrane_example.csv --pulleys 0.1,0,0.1,0",
                   "command line: --pulleys: pulleys A and B coincide");
  expectInputError(
      "assets/data/membrane_example.csv --pulleys 0.1,0,0.2",
      "command line: --pulleys: must be AX,AY,BX,BY, 4 finite numbers (got \"0.1,0,0.2\")");
  expectInputError(
      "assets/data/membrane_example.csv --pulleys 0.1,nan,0.2,0",
      "command line: --pulleys: must be AX,AY,BX,BY, 4 finite numbers (got \"0.1,nan,0.2,0\")");
  expectInputError("assets/data/membrane_example.csv", "command line: --pulleys: is required");
}

TEST(FitCli, BadGenerateOptionsExitTwo) {
  const std::string out = (fitScratch() / "never.csv").string();
  expectInputError("--generate " + out + " " + kPulleys + " --preload 0.8",
                   "command line: --k: is required with --generate");
  expectInputError("--generate " + out + " " + kPulleys + " --k 25 --preload -1",
                   "command line: --preload: must be >= 0");
  expectInputError(
      "--generate " + out + " " + kPulleys + " --k 25 --preload 1 --grid 4by4",
      "command line: --grid: must be WxH, each a whole number in [1, 1000000] (got \"4by4\")");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
