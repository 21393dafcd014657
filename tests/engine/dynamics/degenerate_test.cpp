// The degenerate-geometry corpus (tests/data/degenerate/): each scene either runs with the guards
// doing their job (finite state every step, a warning where a guard repaired the geometry) or is
// stopped with a clear InputError / SimulationError. Never NaN, never another exception.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

enum class Expect { Refused, Runs, RunsWithWarning, RunsOrStops, WarnsOrRefused };

struct Outcome {
  bool refused = false, stopped = false;
  std::string message;
  std::vector<std::string> warnings;
  int firstWraps = -1;
};

Outcome simulate(const std::string& path, int steps) {
  Outcome o;
  try {
    World world(loadSceneFile(path), path);
    for (int i = 0; i < steps; ++i) {
      world.step(world.scene().dt, world.scene().substeps);
      if (i == 0) o.firstWraps = world.cable(0).wraps();
      for (int b = 0; b < world.bodyCount(); ++b) {
        const BodyState& s = world.body(b);
        EXPECT_TRUE(isFinite(s.position) && isFinite(s.velocity) && std::isfinite(s.angle))
            << path << " step " << i;
      }
      for (int c = 0; c < world.cableCount(); ++c) {
        EXPECT_TRUE(std::isfinite(world.cable(c).length())) << path << " step " << i;
        EXPECT_TRUE(std::isfinite(world.cable(c).tension())) << path << " step " << i;
        EXPECT_GE(world.cable(c).tension(), 0.0) << path << " step " << i;
      }
      EXPECT_FALSE(std::isnan(world.energy())) << path;
    }
    o.warnings = world.warnings();
  } catch (const InputError& e) {
    o.refused = true;
    o.message = e.what();
  } catch (const SimulationError& e) {
    o.stopped = true;
    o.message = e.what();
  }
  return o;
}

TEST(Degenerate, EveryCorpusSceneRunsGuardedOrStopsCleanly) {
  const std::map<std::string, Expect> expected = {
      {"coincident_anchors", Expect::Refused},
      {"coincident_anchors_via_pulley", Expect::Runs},
      {"zero_length_segment", Expect::RunsWithWarning},
      {"coincident_pulleys", Expect::RunsWithWarning},
      {"pulley_inside_hull", Expect::WarnsOrRefused},
      {"polygon_beyond_segment", Expect::Runs},
      {"huge_and_tiny_masses", Expect::RunsOrStops},
      {"tiny_mass_on_band", Expect::RunsOrStops},
      {"stiff_band_k1e7", Expect::RunsOrStops},
      {"stiff_band_huge_mass", Expect::RunsOrStops},
  };
  int seen = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(test::sourcePath("tests/data/degenerate"))) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    ASSERT_TRUE(expected.count(name)) << "no expectation for " << entry.path();
    ++seen;
    const Outcome o = simulate(entry.path().string(), 300);
    std::string summary = o.refused   ? "refused: " + o.message
                          : o.stopped ? "stopped: " + o.message
                                      : "ran";
    for (const auto& w : o.warnings) summary += "\n  warning: " + w;
    SCOPED_TRACE(name + ": " + summary);
    if (o.refused || o.stopped) {
      EXPECT_NE(o.message.find(':'), std::string::npos) << "a clear message names the culprit";
    }
    switch (expected.at(name)) {
      case Expect::Refused:
        EXPECT_TRUE(o.refused);
        break;
      case Expect::Runs:
        EXPECT_FALSE(o.refused || o.stopped);
        break;
      case Expect::RunsWithWarning:
        EXPECT_FALSE(o.refused || o.stopped);
        EXPECT_FALSE(o.warnings.empty());
        break;
      case Expect::RunsOrStops:
        EXPECT_FALSE(o.refused);
        break;
      case Expect::WarnsOrRefused:
        EXPECT_TRUE(o.refused || !o.warnings.empty());
        break;
    }
    if (name == "polygon_beyond_segment") {
      EXPECT_EQ(o.firstWraps, 0) << "the polygon lies beyond the segment: not wrapped";
    }
    std::printf("[degenerate] %s\n", summary.c_str());
  }
  EXPECT_EQ(seen, static_cast<int>(expected.size()));
}

// A rigid cable authored shorter than its path snaps taut to its rest length: a warning names it
// at the start (and none for one that starts taut).
TEST(Degenerate, ARigidCableLongerThanItsRestLengthIsNamedAtTheStart) {
  for (const double rest : {1.0, 3.0}) {
    SceneDef scene;
    BodyDef weight;
    weight.name = "weight";
    weight.position = Vec2(0, -3);
    weight.shapes = {ShapeDef{}};
    scene.bodies = {weight};
    CableDef rope;
    rope.name = "rope";
    rope.end.body = "weight";
    rope.restLength = rest;
    scene.cables = {rope};
    const World world(scene);
    if (rest < 3) {
      ASSERT_EQ(world.warnings().size(), 1u);
      EXPECT_NE(world.warnings()[0].find("cable 'rope': rigid and 2 m longer"), std::string::npos)
          << world.warnings()[0];
    } else {
      EXPECT_TRUE(world.warnings().empty()) << world.warnings()[0];
    }
  }
}

}  // namespace
}  // namespace cablelab
