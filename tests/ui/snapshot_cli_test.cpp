// `cablelab snapshot` and `cablelab gui` argument handling (no display needed: with --frames or
// --screenshot, bad input must fail before the sandbox opens a window, so these run without one).
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>

#include "engine/core/error.h"
#include "tests/ui/test_support.h"
#include "ui/image.h"
#include "ui/offscreen.h"
#include "ui/sandbox.h"
#include "ui/scene_catalog.h"

namespace cablelab::test {
namespace {

TEST(SnapshotCli, WritesAPngOfTheRequestedSize) {
  const auto list = ui::builtinSceneList();
  ASSERT_FALSE(list.empty());
  const std::string out = (outputDir("cli") / "snap.png").string();
  const RunResult r = run(std::string(CABLELAB_CLI) + " snapshot " + list.front().name + " --out " +
                              out + " --size 320x200 --time 0.1",
                          "snapshot_ok");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ui::Image image = ui::readPng(out);
  EXPECT_EQ(image.width, 320);
  EXPECT_EQ(image.height, 200);
}

TEST(SnapshotCli, BadInputExitsTwoWithOneLine) {
  const std::string out = (outputDir("cli") / "bad.png").string();
  const std::string scene = ui::builtinSceneList().front().name;
  for (const char* size : {"12", "0x100", "100x", "axb", "100x100x3", "-5x10"}) {
    const RunResult r =
        run(std::string(CABLELAB_CLI) + " snapshot " + scene + " --out " + out + " --size " + size,
            "snapshot_bad_size");
    EXPECT_EQ(r.exitCode, 2) << size;
    EXPECT_NE(r.err.find("size"), std::string::npos) << r.err;
  }
  const RunResult missing =
      run(std::string(CABLELAB_CLI) + " snapshot /nonexistent/scene.json --out " + out,
          "snapshot_missing");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("/nonexistent/scene.json"), std::string::npos) << missing.err;
  const RunResult time =
      run(std::string(CABLELAB_CLI) + " snapshot " + scene + " --out " + out + " --time -1",
          "snapshot_bad_time");
  EXPECT_EQ(time.exitCode, 2) << time.err;
}

// A snapshot colours tensions on the window's scale for the scene (10 N for the hexagon: its
// 1 kg weight), not on one of its own (a 2 s run's largest tension made it 20 N).
TEST(SnapshotCli, ColoursTensionsOnTheWindowsScale) {
  ui::Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hexagon"));
  const double windowScale = sandbox.tensionScale;
  ASSERT_EQ(windowScale, 10);
  const std::string out = (outputDir("cli") / "hexagon-scale.png").string();
  const RunResult r = run(
      std::string(CABLELAB_CLI) + " snapshot hexagon --out " + out + " --size 400x300 --time 0.5",
      "snapshot_scale");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const ui::Image snapshot = ui::readPng(out);
  const auto world = sceneAt("hexagon", 0.5);
  ui::RenderOptions options;
  options.tensionScale = windowScale;
  const ui::Image window = ui::renderSnapshot(*world, 400, 300, {}, options);
  EXPECT_LE(countDiffering(snapshot, window, 8), 20);
  options.tensionScale = 2 * windowScale;  // another scale shows: the check can fail
  EXPECT_GT(countDiffering(snapshot, ui::renderSnapshot(*world, 400, 300, {}, options), 8), 200);
}

TEST(SnapshotCli, HelpWorks) {
  EXPECT_EQ(run(std::string(CABLELAB_CLI) + " snapshot --help", "snapshot_help").exitCode, 0);
  EXPECT_EQ(run(std::string(CABLELAB_CLI) + " gui --help", "gui_help").exitCode, 0);
}

namespace fs = std::filesystem;

const std::string kCli = CABLELAB_CLI;
/// The sandbox executable `cablelab gui` hands off to.
const std::string kGui = (fs::path(CABLELAB_CLI).parent_path() / "cablelab-gui").string();
/// No display: a program that tried to open a window would fail with another message.
const std::string kNoDisplay = "env -u DISPLAY -u WAYLAND_DISPLAY ";

std::string data(const std::string& name) {
  return std::string(CABLELAB_SOURCE_DIR) + "/tests/data/bad/" + name;
}

/// A bad input (SCENE and options) and the one line every command prints for it, or, where the
/// line lists the built-in scenes or parameters, its start and end.
struct BadInput {
  std::string kind, args, line, lineEnd = {};
  bool matches(const std::string& err) const {
    if (lineEnd.empty()) return err == line + "\n";
    return err.rfind(line, 0) == 0 && err.size() >= lineEnd.size() + 1 &&
           err.compare(err.size() - lineEnd.size() - 1, lineEnd.size() + 1, lineEnd + "\n") == 0 &&
           std::count(err.begin(), err.end(), '\n') == 1;
  }
};

std::vector<BadInput> badScenes() {
  const std::string folder = (outputDir("gui-bad") / "a_folder.json").string();
  fs::create_directories(folder);
  return {
      {"negative mass", data("scene_negative_mass.json"),
       data("scene_negative_mass.json") + ": bodies[0].mass: must be positive (got -1)"},
      {"bad JSON", data("scene_not_json.json"),
       data("scene_not_json.json") +
           ": (json): not valid JSON at line 1, column 28: syntax error while parsing object key - "
           "unexpected '}'; expected string literal (got \"}\")"},
      {"unknown body in a cable", data("scene_unknown_cable_body.json"),
       data("scene_unknown_cable_body.json") +
           ": cables[0].end.body: unknown body (got \"ghost\")"},
      {"missing file", "/no/such/scene.json",
       "/no/such/scene.json: (file): cannot open: No such file or directory (got "
       "\"/no/such/scene.json\")"},
      {"a directory", folder,
       folder + ": (file): is a directory, not a file" + cablelab::gotValue(folder)},
      {"unknown scene name", "no_such_scene",
       "command line: SCENE: no such built-in scene or file; built-in: ",
       "(got \"no_such_scene\")"},
      {"bad --set name", "hexagon --set nosuch=1",
       "command line: --set nosuch: unknown parameter of scene hexagon (known: ", ")"},
      {"bad --set value", "wheel --set m1=-2", "command line: --set m1: must be positive (got -2)"},
  };
}

TEST(GuiCli, EveryBadSceneExitsTwoWithSnapshotsLineAndNoWindowOrPng) {
  const std::string shot = (outputDir("gui-bad") / "never.png").string();
  for (const BadInput& bad : badScenes()) {
    fs::remove(shot);
    const RunResult snap = run(kCli + " snapshot " + bad.args + " --out " + shot, "bad_snapshot");
    EXPECT_EQ(snap.exitCode, 2) << bad.kind;
    EXPECT_EQ(std::count(snap.err.begin(), snap.err.end(), '\n'), 1)
        << bad.kind << ": " << snap.err;
    EXPECT_TRUE(bad.matches(snap.err)) << bad.kind << ": " << snap.err;
    EXPECT_FALSE(fs::exists(shot)) << bad.kind;
    // `cablelab gui` (handing off) and cablelab-gui itself, with --frames and --screenshot, with
    // --frames alone and with --screenshot alone: the same line, exit 2, no window, no PNG.
    for (const std::string& command :
         {kCli + " gui " + bad.args + " --frames 30 --screenshot " + shot,
          kCli + " gui " + bad.args + " --frames 30",
          kGui + " " + bad.args + " --screenshot " + shot, kGui + " " + bad.args + " --frames 5"}) {
      const RunResult gui = run(kNoDisplay + command, "bad_gui");
      EXPECT_EQ(gui.exitCode, 2) << command;
      EXPECT_EQ(gui.err, snap.err) << command;
      EXPECT_EQ(gui.out, "") << command;
      EXPECT_FALSE(fs::exists(shot)) << command;
    }
  }
}

TEST(GuiCli, BadOptionValuesExitTwoWithOneLine) {
  const std::string shot = (outputDir("gui-bad") / "never.png").string();
  fs::remove(shot);
  const std::pair<std::string, std::string> cases[] = {
      {"--size axb",
       "command line: --size: must be WxH, each a whole number in [240, 16384] (got \"axb\")"},
      {"--size 100x100",
       "command line: --size: must be WxH, each a whole number in [240, 16384] (got \"100x100\")"},
      {"--ui-scale 9", "command line: --ui-scale: must be a number in [0.5, 4] (got \"9\")"},
      {"--set m1", "command line: --set: must be NAME=VALUE (got \"m1\")"},
      {"--record /no/such/dir/clip.gif",
       "command line: --record: cannot write the file: no folder /no/such/dir (got "
       "\"/no/such/dir/clip.gif\")"},
  };
  for (const auto& [args, line] : cases)
    for (const std::string& program : {kCli + " gui", kGui}) {
      const RunResult r =
          run(kNoDisplay + program + " wheel " + args + " --frames 3 --screenshot " + shot,
              "bad_gui_option");
      EXPECT_EQ(r.exitCode, 2) << program << " " << args;
      EXPECT_EQ(r.err, line + "\n") << program << " " << args;
      EXPECT_FALSE(fs::exists(shot));
    }
  // The snapshot says the same of a bad --set.
  const RunResult snap = run(kCli + " snapshot wheel --set m1 --out " + shot, "bad_snapshot_set");
  EXPECT_EQ(snap.err, "command line: --set: must be NAME=VALUE (got \"m1\")\n");
}

/// The long options a --help text lists.
std::set<std::string> optionsIn(const std::string& help) {
  static const std::regex option(R"(--[a-z][a-z-]*)");
  std::set<std::string> found;
  for (std::sregex_iterator i(help.begin(), help.end(), option), end; i != end; ++i)
    found.insert(i->str());
  return found;
}

TEST(GuiCli, HelpListsEveryOptionOfTheSandboxInBothPrograms) {
  const RunResult cli = run(kCli + " gui --help", "gui_help_all");
  const RunResult gui = run(kGui + " --help", "gui_help_sibling");
  ASSERT_EQ(cli.exitCode, 0);
  ASSERT_EQ(gui.exitCode, 0);
  const std::set<std::string> listed = optionsIn(cli.out);
  for (const char* option :
       {"--set", "--frames", "--screenshot", "--size", "--ui-scale", "--record", "--script",
        "--script-out", "--open", "--test-input", "--help"})
    EXPECT_TRUE(listed.count(option)) << option << " missing from `cablelab gui --help`:\n"
                                      << cli.out;
  EXPECT_EQ(listed, optionsIn(gui.out)) << cli.out << "\n---\n" << gui.out;
}

}  // namespace
}  // namespace cablelab::test
