// Scene files: round trips, the shipped assets, and bad files named field by field.
#include "engine/model/scene_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

TEST(SceneJson, EveryBuiltinSceneRoundTrips) {
  for (const SceneInfo& info : builtinScenes()) {
    const SceneDef scene = makeScene(info.name);
    const nlohmann::json once = sceneToJson(scene);
    const nlohmann::json twice = sceneToJson(sceneFromJson(once, info.name));
    EXPECT_EQ(once, twice) << info.name;
    EXPECT_GT(scene.bodies.size(), 0u) << info.name;
  }
}

TEST(SceneJson, ShippedAssetsAreTheBuiltinScenes) {
  for (const SceneInfo& info : builtinScenes()) {
    const SceneDef file = loadSceneFile(test::sourcePath("assets/scenes/" + info.name + ".json"));
    EXPECT_EQ(sceneToJson(file), sceneToJson(makeScene(info.name)))
        << "regenerate with: cablelab scenes --export assets/scenes";
  }
}

TEST(SceneJson, SetOverridesAParameterAndRejectsUnknownOnes) {
  const SceneDef scene = makeScene("ballast", {{"l", 2.5}});
  EXPECT_DOUBLE_EQ(scene.cables[0].start.point.x(), -2.5);
  try {
    makeScene("ballast", {{"length", 1}});
    FAIL() << "unknown parameter accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "--set length");
  }
  EXPECT_THROW(makeScene("ballast", {{"m_point", -1}}), InputError);
  EXPECT_THROW(parseSetting("l=abc"), InputError);
  EXPECT_THROW(parseSetting("l"), InputError);
  EXPECT_EQ(parseSetting("v0y=2.5").second, 2.5);
}

struct BadScene {
  const char* file;
  const char* field;
};

// Each file breaks one thing; the CLI must exit 2 with one line naming the file and the field.
const BadScene kBadScenes[] = {
    {"scene_negative_mass.json", "bodies[0].mass"},
    {"scene_zero_rest_length.json", "cables[0].rest_length"},
    {"scene_unknown_cable_body.json", "cables[0].end.body"},
    {"scene_polygon_not_convex.json", "bodies[1].shapes[0].vertices"},
    // Box2D would abort on these two: vertices it merges, an area under float's epsilon.
    {"scene_box_too_small.json", "bodies[0].shapes[0].vertices"},
    {"scene_polygon_too_thin.json", "bodies[1].shapes[0].vertices"},
    {"scene_unknown_key.json", "bodies[0].mas"},
    {"scene_position_wrong_size.json", "bodies[0].position"},
    {"scene_position_not_number.json", "bodies[0].position[0]"},
    {"scene_duplicate_body.json", "bodies[1].name"},
    {"scene_bad_shape_type.json", "bodies[0].shapes[0].type"},
    {"scene_negative_radius.json", "bodies[0].shapes[0].radius"},
    {"scene_bad_side.json", "cables[0].pulleys[0].side"},
    {"scene_joint_unknown_body.json", "joints[0].body_b"},
    {"scene_limits_reversed.json", "joints[0].limits"},
    {"scene_negative_stiffness.json", "cables[0].stiffness"},
    {"scene_threaded_polygon.json", "cables[0].pulleys[0].side"},
    {"scene_cable_without_name.json", "cables[0].name"},
    {"scene_zero_dt.json", "dt"},
    {"scene_dt_too_long.json", "dt"},  // 1000 s: ran no step at all for --time 2
    {"scene_bodies_not_list.json", "bodies"},
    {"scene_coincident_cable_ends.json", "cables[0]"},
    {"scene_unknown_body_type.json", "bodies[0].type"},
    {"scene_not_json.json", "(json)"},
    {"scene_infinite_mass.json", "(json)"},
    // Circles, drums and wheels (the good twin: tests/data/wheels/good_wheels_scene.json).
    {"scene_circle_no_radius.json", "cables[0].pulleys[0].radius"},
    {"scene_circle_negative_mu.json", "cables[1].pulleys[0].mu"},
    {"scene_circle_threaded.json", "cables[0].pulleys[1].side"},
    {"scene_drum_zero_turns.json", "cables[1].end.turns"},
    {"scene_no_slip_elastic.json", "cables[0].pulleys[0].no_slip"},
    {"scene_mu_and_no_slip.json", "cables[1].pulleys[0].mu"},
    {"scene_drum_threaded.json", "cables[1].end.side"},
    // Polygons with friction (the good twin: tests/data/polygon_friction/).
    {"scene_polygon_negative_mu.json", "cables[0].pulleys[0].mu"},
    {"scene_polygon_mu_and_no_slip.json", "cables[0].pulleys[0].mu"},
    {"scene_polygon_no_slip.json", "cables[0].pulleys[0].no_slip"},
};

TEST(SceneJson, BadFilesExitTwoNamingTheField) {
  for (const BadScene& bad : kBadScenes) {
    const std::string path = test::sourcePath(std::string("tests/data/bad/") + bad.file);
    const auto r = test::runCli("run '" + path + "' --time 0.1");
    EXPECT_EQ(r.exitCode, 2) << bad.file << ": " << r.err;
    EXPECT_NE(r.err.find(path + ": " + bad.field), std::string::npos)
        << bad.file << " said: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad.file << " said: " << r.err;
  }
}

// A value a user can fix is quoted back, `SOURCE: FIELD: what is wrong (got VALUE)` (docs/cli.md):
// a polygon that is not convex gave no vertices, mu with no_slip neither value, a number beyond
// double range no number, a threaded polygon or a wound auto pulley no side.
TEST(SceneJson, BadValuesAreQuotedBack) {
  const std::pair<const char*, const char*> kQuoted[] = {
      {"scene_polygon_not_convex.json", "(got [[0, 0], [2, 0], [1, 0.2], [2, 2], [0, 2]])"},
      {"scene_mu_and_no_slip.json", "(got mu 0.2 with no_slip true)"},
      {"scene_polygon_mu_and_no_slip.json", "(got mu 0.2 with no_slip true)"},
      {"scene_polygon_no_slip.json", "(got true)"},
      {"scene_circle_threaded.json", "(got \"threaded\")"},
      {"scene_threaded_polygon.json", "(got \"threaded\")"},
      {"scene_infinite_mass.json", "(json): a number beyond double range (got 1e999)"},
  };
  for (const auto& [file, got] : kQuoted) {
    const std::string path = test::sourcePath(std::string("tests/data/bad/") + file);
    const auto r = test::runCli("run '" + path + "' --time 0.1");
    EXPECT_EQ(r.exitCode, 2) << file << ": " << r.err;
    EXPECT_EQ(r.err.size() - r.err.find(got), std::string(got).size() + 1) << file << ": " << r.err;
  }
  SceneDef wound = makeScene("hexagon");
  for (CableDef& c : wound.cables)
    for (PulleyDef& p : c.pulleys)
      if (p.kind != PulleyDef::Kind::Point) p.side = WrapSide::Auto, p.turns = 2;
  try {
    validateScene(wound, "scene");
    ADD_FAILURE() << "a wound auto pulley was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs side left or right (got \"auto\")"),
              std::string::npos)
        << e.what();
  }
}

// Box2D merges a collision polygon's vertices closer than 2.5 mm and goes on while three are left:
// so does the check (a random scene had a pentagon with two vertices 1.8 mm apart).
TEST(SceneJson, APolygonBox2DMergesTwoVerticesOfIsAccepted) {
  SceneDef scene = makeScene("hexagon");
  std::vector<Vec2>& v = scene.bodies[0].shapes[0].vertices;
  ASSERT_GE(v.size(), 4u);
  // On the hexagon's circle 1.8 mm on from its first vertex: still strictly convex.
  const double r = v[0].norm(), a = std::atan2(v[0].y(), v[0].x()) + 0.0018 / r;
  v.insert(v.begin() + 1, r * Vec2(std::cos(a), std::sin(a)));
  EXPECT_NO_THROW(validateScene(scene, "scene"));
  World world(scene);
  world.step(scene.dt, scene.substeps);
  EXPECT_TRUE(isFinite(world.body(0).position));
}

TEST(SceneJson, TheGoodTwinOfTheBadFilesRuns) {
  // The bad files are mutations of this one: it must load, so each bad file fails for its own
  // reason.
  const auto r =
      test::runCli("run '" + test::sourcePath("tests/data/good_scene.json") + "' --time 0.1");
  EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(SceneJson, ThePolygonFrictionExampleRunsRoundTripsAndWritesSpanTensions) {
  const std::string path =
      test::sourcePath("tests/data/polygon_friction/good_polygon_friction_scene.json");
  const std::string csv = "/tmp/cablelab-polygon-friction-test.csv";
  const auto r = test::runCli("run '" + path + "' --time 0.5 --csv " + csv);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const SceneDef scene = loadSceneFile(path);
  const PulleyDef& square = scene.cables[0].pulleys[0];
  EXPECT_EQ(square.kind, PulleyDef::Kind::Polygon);
  EXPECT_EQ(square.grip, Grip::Capstan);
  EXPECT_DOUBLE_EQ(square.mu, 0.2);
  EXPECT_EQ(sceneToJson(sceneFromJson(sceneToJson(scene), "again")), sceneToJson(scene));
  // "mu": 0 is no friction at all: the same scene as without it.
  nlohmann::json j = sceneToJson(scene);
  j["cables"][0]["pulleys"][0]["mu"] = 0;
  nlohmann::json without = j;
  without["cables"][0]["pulleys"][0].erase("mu");
  EXPECT_EQ(sceneToJson(sceneFromJson(j, "mu0")), sceneToJson(sceneFromJson(without, "none")));
  // 3 kg against 1 kg slides (e^(0.2 pi) = 1.87): the CSV's span columns are in that ratio.
  std::ifstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line)) last = line;
  std::remove(csv.c_str());
  auto column = [&](const std::string& name) {
    const size_t at = header.find(name);
    EXPECT_NE(at, std::string::npos) << name << " in " << header;
    const long index = std::count(header.begin(), header.begin() + at, ',');
    std::stringstream row(last);
    std::string cell;
    for (long i = 0; i <= index; ++i) std::getline(row, cell, ',');
    return std::stod(cell);
  };
  EXPECT_NEAR(column("rope.span0.tension") / column("rope.span1.tension"), std::exp(0.2 * M_PI),
              1e-6);
}

TEST(SceneJson, TheWheelsExampleRunsAndRoundTrips) {
  const std::string path = test::sourcePath("tests/data/wheels/good_wheels_scene.json");
  const auto r = test::runCli("run '" + path + "' --time 0.5");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  const SceneDef scene = loadSceneFile(path);
  const PulleyDef& wheel = scene.cables[0].pulleys[0];
  EXPECT_EQ(wheel.kind, PulleyDef::Kind::Circle);
  EXPECT_EQ(wheel.grip, Grip::NoSlip);
  EXPECT_EQ(scene.cables[0].pulleys[1].side, WrapSide::Auto);
  EXPECT_EQ(scene.cables[1].pulleys[0].grip, Grip::Capstan);
  EXPECT_DOUBLE_EQ(scene.cables[1].end.radius, 0.1);
  EXPECT_DOUBLE_EQ(scene.joints[1].servo.speed, 1.0);
  EXPECT_EQ(sceneToJson(sceneFromJson(sceneToJson(scene), "again")), sceneToJson(scene));
}

TEST(SceneJson, MissingFileAndUnknownSceneExitTwo) {
  auto r = test::runCli("run /no/such/scene.json");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("/no/such/scene.json"), std::string::npos);
  r = test::runCli("run ballast --set nope=1");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("nope"), std::string::npos);
  r = test::runCli("run ballast --dt -1");
  EXPECT_EQ(r.exitCode, 2);
}

}  // namespace
}  // namespace cablelab
