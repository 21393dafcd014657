// Bad input exits 2 with one line `SOURCE: FIELD: what is wrong (got VALUE)` from every
// subcommand (engine/core/error.h): missing files, directories, unwritable outputs, an empty
// scene, unknown keys, bad option values, and one number format in every message.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& name) {
  return test::dataPath(name);
}

// A scratch folder of this test's own, with a few input files in it.
const fs::path& scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("cablelab_input_errors_" + std::to_string(getpid()));
    fs::create_directories(d / "a_folder.json");
    std::ofstream(d / "empty_scene.json") << "{}";
    std::ofstream(d / "no_bodies.json") << R"({"bodies": [], "cables": []})";
    std::ofstream(d / "wrap_unknown_key.json")
        << R"({"A": [-2, 0], "B": [2, 0], "polygon": [[-1,-1],[1,-1],[1,1],[-1,1]],
              "side": "left", "colour": "red"})";
    std::ofstream(d / "scene_negative_mass.json") << R"({"bodies": [{"name": "b", "mass": -1.5}]})";
    std::ofstream(d / "polygon_pulley_on_a_disc.json")
        << R"({"bodies": [{"name": "drum", "shapes": [{"type": "circle"}]},
                          {"name": "w", "position": [0.5, -1]}],
              "cables": [{"name": "c", "start": {"point": [-0.5, 1]}, "end": {"body": "w"},
                          "pulleys": [{"type": "polygon", "body": "drum"}]}]})";
    std::ofstream(d / "statics_huge_k.json")
        << R"({"cables": [{"a": [0, 0], "b": [1, 0], "k": 1e13, "L": 1}]})";
    return d;
  }();
  return dir;
}

std::string file(const std::string& name) {
  return (scratch() / name).string();
}

struct Expect {
  std::string args;     // after `cablelab`
  std::string message;  // the whole stderr line, without the newline
};

// Exit 2, nothing on stdout, exactly `message` as one line on stderr.
void expectError(const Expect& e) {
  const auto r = test::runCli(e.args);
  EXPECT_EQ(r.exitCode, 2) << e.args << "\n" << r.err;
  EXPECT_EQ(r.out, "") << e.args;
  EXPECT_EQ(r.err, e.message + "\n") << e.args;
}

TEST(InputErrors, AMissingFileReadsTheSameEverywhere) {
  const std::string missing = "/no/such/input.json";
  const std::string said =
      missing + ": (file): cannot open: No such file or directory" + cablelab::gotValue(missing);
  for (const std::string& args : {"run " + missing, "wrap " + missing, "statics " + missing,
                                  "fit " + missing + " --pulleys -0.2,0,0.2,0"})
    expectError({args, said});
}

TEST(InputErrors, ADirectoryAsAnInputFileExitsTwo) {
  const std::string dir = file("a_folder.json");
  const std::string said = dir + ": (file): is a directory, not a file" + cablelab::gotValue(dir);
  for (const std::string& args :
       {"run " + dir, "wrap " + dir, "statics " + dir, "fit " + dir + " --pulleys -0.2,0,0.2,0"})
    expectError({args, said});
}

TEST(InputErrors, AnUnwritableOutputExitsTwoBeforeRunning) {
  const std::string bad = "/no/such/folder/out";
  auto said = [&](const std::string& option, const std::string& ext) {
    return "command line: " + option +
           ": cannot write the file: no folder /no/such/folder (got \"" + bad + ext + "\")";
  };
  expectError({"run pulley --time 0.1 --csv " + bad + ".csv", said("--csv", ".csv")});
  expectError({"track --time 0.1 --csv " + bad + ".csv", said("--csv", ".csv")});
  expectError({"fit --generate " + bad + ".csv --pulleys -0.2,0,0.2,0 --k 25 --preload 0.8",
               said("--generate", ".csv")});
#ifdef CABLELAB_HAVE_OFFSCREEN
  expectError({"run pulley --time 0.1 --png " + bad + ".png", said("--png", ".png")});
  expectError({"snapshot pulley --out " + bad + ".png", said("--out", ".png")});
  expectError({"record pulley --time 0.1 --out " + bad + ".gif", said("--out", ".gif")});
  expectError({"track --time 0.1 --png " + bad + ".png", said("--png", ".png")});
  expectError({"reach --grid 2 --png " + bad + ".png", said("--png", ".png")});
  // A folder is not a file either.
  expectError({"snapshot pulley --out " + scratch().string(),
               "command line: --out: cannot write the file: it is a directory (got \"" +
                   scratch().string() + "\")"});
#endif
}

TEST(InputErrors, AnEmptySceneIsBadInput) {
  for (const char* name : {"empty_scene.json", "no_bodies.json"})
    expectError({"run " + file(name),
                 file(name) + ": bodies: must list at least one body (the scene has none)"});
}

TEST(InputErrors, NoCablesAndCoincidentEndsSayWhatIsWrong) {
  expectError(
      {"statics " + data("bad/statics_no_cables.json"),
       data("bad/statics_no_cables.json") + ": cables: must list at least one cable (got none)"});
  expectError({"run " + data("bad/scene_coincident_cable_ends.json"),
               data("bad/scene_coincident_cable_ends.json") +
                   ": cables[0]: must not have zero length: its ends coincide at the initial pose "
                   "(got 0 m)"});
}

TEST(InputErrors, WrapRejectsUnknownKeysLikeEveryOtherInput) {
  expectError({"wrap " + file("wrap_unknown_key.json"),
               file("wrap_unknown_key.json") + ": colour: unknown key"});
  expectError({"statics " + data("bad/statics_unknown_key.json"),
               data("bad/statics_unknown_key.json") + ": cables[0].stiffness: unknown key"});
  expectError({"run " + data("bad/scene_unknown_key.json"),
               data("bad/scene_unknown_key.json") + ": bodies[0].mas: unknown key"});
}

TEST(InputErrors, NumbersInMessagesHaveOneFormat) {
  // Shortest text that reads back as the same double: -1.5, 1e+13, never -1.500000.
  expectError({"run " + file("scene_negative_mass.json"),
               file("scene_negative_mass.json") + ": bodies[0].mass: must be positive (got -1.5)"});
  expectError(
      {"statics " + file("statics_huge_k.json"),
       file("statics_huge_k.json") + ": cables[0].k: must be at most 1e12 N/m (got 1e+13)"});
  expectError({"run ballast --set l=-0.25", "command line: --set l: must be positive (got -0.25)"});
  expectError({"run ballast --dt 2", "command line: --dt: must be in (0, 1] s (got 2)"});
}

TEST(InputErrors, BadOptionValuesNameTheOption) {
  expectError({"run ballast --set l", "command line: --set: must be NAME=VALUE (got \"l\")"});
  expectError(
      {"run ballast --set l=1x", "command line: --set l: must be a finite number (got \"1x\")"});
  expectError({"track --target 1,2,3,4",
               "command line: --target: must be X,Y or X,Y,THETA, 2 or 3 finite numbers (got "
               "\"1,2,3,4\")"});
  expectError({"track --target 1,2,3",
               "command line: --target: THETA needs a box that may turn (scene parameter turn=1) "
               "(got 3)"});
#ifdef CABLELAB_HAVE_OFFSCREEN  // snapshot exists only with the offscreen renderer
  expectError({"snapshot pulley --out x.png --size 800by600",
               "command line: --size: must be WxH, each a whole number in [16, 8192] (got "
               "\"800by600\")"});
#endif
  expectError({"statics " + data("statics/two_cables.json") + " --solver magic",
               "command line: --solver: must be auto, socp or newton (got \"magic\")"});
  expectError({"run ballast --time abc",
               "command line: --time: cannot convert the value (got \"abc\") (see cablelab run "
               "--help)"});
  expectError({"run", "command line: scene: is required (got nothing) (see cablelab run --help)"});
}

TEST(InputErrors, ASetThatBreaksABuiltInSceneNamesTheSetTheUserTyped) {
  // Not "scene 'winch': joints[0].servo.speed: ...": the user wrote no such field.
  expectError({"run winch --set omega=1e308",
               "command line: --set omega: makes scene winch invalid (joints[0].servo.speed: must "
               "be within +/-1e12 (got 1e+308)) (got \"omega=1e+308\")"});
  expectError({"run ballast --set l=1e13",
               "command line: --set l: makes scene ballast invalid (view.center: must be within "
               "+/-1e12 (got -4e+12)) (got \"l=1e+13\")"});
  // Two settings: either may be the one; both are quoted.
  const auto r = test::runCli("run tackle --set m_load=3 --set r=1e-9");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(r.err.rfind("command line: --set: makes scene tackle invalid (bodies[", 0), 0u)
      << r.err;
  EXPECT_NE(r.err.find(") (got \"m_load=3 r=1e-09\")\n"), std::string::npos) << r.err;
}

TEST(InputErrors, APolygonPulleyWithoutVerticesOnABodyWithoutAPolygonSaysSo) {
  // Without vertices it takes the body's polygon; a disc has none to give.
  expectError({"run " + file("polygon_pulley_on_a_disc.json"),
               file("polygon_pulley_on_a_disc.json") +
                   ": cables[0].pulleys[0].vertices: is required: body \"drum\" has no polygon "
                   "or box shape to take them from (got nothing)"});
}

TEST(InputErrors, EveryBadInputFileGivesOneLineInTheStyle) {
  // SOURCE: FIELD: what, one line, for every file under tests/data/bad/.
  const std::regex style(R"(^[^:\n]+: [^:\n]+: [^\n]+\n$)");
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::sourcePath("tests/data/bad"))) {
    const std::string name = entry.path().filename().string();
    const std::string path = entry.path().string();
    std::string args;
    if (name.rfind("scene_", 0) == 0)
      args = "run " + path;
    else if (name.rfind("statics_", 0) == 0)
      args = "statics " + path;
    else if (name.rfind("wrap_", 0) == 0)
      args = "wrap " + path;
    else if (name.rfind("fit_", 0) == 0)
      args = "fit " + path + " --pulleys -0.2,0,0.2,0";
    else
      continue;
    ++files;
    const auto r = test::runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
    EXPECT_TRUE(std::regex_match(r.err, style)) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind(path + ": ", 0), 0u) << "SOURCE is the file: " << r.err;
  }
  EXPECT_GE(files, 40);
}

TEST(InputErrors, TheSandboxReadsItsArgumentsTheSameWay) {
  const fs::path gui = fs::path(CABLELAB_CLI).parent_path() / "cablelab-gui";
  if (!fs::exists(gui)) GTEST_SKIP() << "built without the sandbox";
  auto run = [&](const std::string& args) { return test::runProgram(gui.string(), args); };
  auto r = run("--size 100x100");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.err,
            "command line: --size: must be WxH, each a whole number in [240, 16384] (got "
            "\"100x100\")\n");
  r = run("--frames -3");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.err,
            "command line: --frames: must be a whole number in [0, 100000000] (got \"-3\")\n");
  r = run("--bogus");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(r.err,
            "command line: (arguments): unknown option or one argument too many (got \"--bogus\") "
            "(see cablelab-gui --help)\n");
  r = run("--help");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("--screenshot"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace cablelab
