// Save writes what the sandbox runs: live cable edits (the inspector, a loaded fit) and the
// scene's joints, in a file that `cablelab run` loads and runs exactly as the sandbox did.
#include "ui/authoring.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/model/scene_json.h"
#include "tests/ui/test_support.h"

namespace cablelab::ui {
namespace {

/// The last row of a `cablelab run --csv` file, by column name.
std::map<std::string, double> lastCsvRow(const std::string& path) {
  std::istringstream in(test::slurp(path));
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::map<std::string, double> row;
  std::istringstream names(header), values(last);
  for (std::string name, value; std::getline(names, name, ',') && std::getline(values, value, ',');)
    row[name] = std::stod(value);
  return row;
}

TEST(SaveScene, WritesLiveCableEditsAndJointsAndRunsAsTheSandboxDid) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hexagon"));
  ASSERT_GT(sandbox.world()->cableCount(), 0);
  ASSERT_FALSE(sandbox.scene.joints.empty());
  // The rigid cable made an elastic band, a little short: the hexagon swings differently.
  sandbox.selectedCable = 0;
  const double initial = sandbox.world()->cable(0).restLength();
  sandbox.cableEdit = {initial - 0.02, 2000, 0.01, 5};
  ASSERT_TRUE(sandbox.applyCableEdit()) << sandbox.error;
  const int steps = 60;
  for (int i = 0; i < steps; ++i) sandbox.advance(sandbox.dt, true);

  const auto dir = test::outputDir("save");
  const std::string file = (dir / "edited-hexagon.json").string();
  saveScene(sandbox, file);
  const nlohmann::json saved = nlohmann::json::parse(test::slurp(file));
  const nlohmann::json& cable = saved["cables"][0];
  EXPECT_DOUBLE_EQ(cable["rest_length"].get<double>(), initial - 0.02);
  EXPECT_DOUBLE_EQ(cable["stiffness"].get<double>(), 2000);
  EXPECT_DOUBLE_EQ(cable["preload"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(cable["damping"].get<double>(), 5);
  EXPECT_EQ(saved["joints"], sceneToJson(sandbox.scene)["joints"]);
  EXPECT_EQ(saved["joints"].size(), sandbox.scene.joints.size());

  // `cablelab run` on the saved file: the same motion as the sandbox's edited world.
  const std::string csv = (dir / "edited-hexagon.csv").string();
  char time[32];
  std::snprintf(time, sizeof time, "%.17g", steps * sandbox.dt);
  const auto r = test::run(
      std::string(CABLELAB_CLI) + " run " + file + " --time " + time + " --csv " + csv, "save_run");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto row = lastCsvRow(csv);
  const World& world = *sandbox.world();
  EXPECT_NEAR(row.at("t"), world.time(), 1e-12);
  for (int b = 0; b < world.bodyCount(); ++b) {
    if (world.scene().bodies[b].type != BodyType::Dynamic) continue;
    const std::string name = world.scene().bodies[b].name;
    EXPECT_NEAR(row.at(name + ".x"), world.body(b).position.x(), 1e-9) << name;
    EXPECT_NEAR(row.at(name + ".y"), world.body(b).position.y(), 1e-9) << name;
    EXPECT_NEAR(row.at(name + ".theta"), world.body(b).angle, 1e-9) << name;
  }
  const std::string c = world.cable(0).name();
  EXPECT_NEAR(row.at(c + ".tension"), world.cable(0).tension(), 1e-6);
}

TEST(SaveScene, UneditedCablesKeepTheirFileRestLength) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hexagon"));
  const SceneDef def = sceneToSave(sandbox);
  ASSERT_EQ(def.cables.size(), sandbox.scene.cables.size());
  for (size_t i = 0; i < def.cables.size(); ++i) {
    EXPECT_EQ(def.cables[i].restLength, sandbox.scene.cables[i].restLength);
    EXPECT_EQ(def.cables[i].stiffness, sandbox.scene.cables[i].stiffness);
  }
}

}  // namespace
}  // namespace cablelab::ui
