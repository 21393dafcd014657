// `cablelab snapshot` and `cablelab gui` argument handling (no display needed).
#include <gtest/gtest.h>

#include "tests/ui/test_support.h"
#include "ui/image.h"
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

TEST(SnapshotCli, HelpWorks) {
  EXPECT_EQ(run(std::string(CABLELAB_CLI) + " snapshot --help", "snapshot_help").exitCode, 0);
  EXPECT_EQ(run(std::string(CABLELAB_CLI) + " gui --help", "gui_help").exitCode, 0);
}

}  // namespace
}  // namespace cablelab::test
