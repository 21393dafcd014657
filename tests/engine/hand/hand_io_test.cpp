// The hand experiments' shared option checks and JSON (hand_io.h), and the grasp sequence with an
// outer-loop law from outside (HandGrasp::beforeStep's GraspLaw).
#include "engine/hand/hand_io.h"

#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/hand/hand_grasp.h"

#include <stdexcept>

namespace cablelab {
namespace {

std::string messageOf(const TrackRequest& q) {
  try {
    trackOptions(q);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HandIo, TrackOptionsAreCheckedWithTheClisMessages) {
  TrackRequest q;
  q.target = Vec2(1, 1);
  q.ramp = std::array<double, 3>{1, 1, 2};
  EXPECT_EQ(messageOf(q),
            "command line: --ramp: give either --target or --ramp, not both (got both)");
  q.target.reset();
  q.ramp = std::array<double, 3>{0.1, 0.1, 0};
  EXPECT_EQ(messageOf(q), "command line: --ramp: SECONDS must be positive (got 0)");
  q.ramp.reset();
  q.target = Vec2(100, 1);
  EXPECT_EQ(messageOf(q),
            "command line: --target: must be a number in [0, 100] (got 100.00499987500625)");
  q.target = Vec2(0.2, 0.1);
  q.start = Vec2(0.5, -2.25);
  EXPECT_EQ(messageOf(q),
            "command line: --start: the fingers cannot pinch the box there (got 0.5,-2.25)");
  q.start = Vec2(-0.1, 0.1);
  q.time = -1;
  EXPECT_EQ(messageOf(q), "command line: --time: must be a number in [0, 1e+05] (got -1)");
  q.time = 4;
  q.pid = true;
  const TrackOptions o = trackOptions(q);
  EXPECT_EQ(o.target, Vec2(0.2, 0.1));
  EXPECT_EQ(*o.start, Vec2(-0.1, 0.1));
  EXPECT_EQ(o.time, 4);
  EXPECT_TRUE(o.pid);
  EXPECT_EQ(o.rampTime, 0);
}

TEST(HandIo, ReachOptionsAreCheckedWithTheClisMessages) {
  auto messageOf = [](int grid, const std::string& model) {
    try {
      reachOptions(grid, model, false);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(messageOf(0, "simulation"),
            "command line: --grid: must be a whole number in [1, 1000] (got 0)");
  EXPECT_EQ(messageOf(5, "dynamic"),
            "command line: --model: must be simulation or quasi-static (got \"dynamic\")");
  const ReachOptions o = reachOptions(7, "quasi-static", true, 3);
  EXPECT_EQ(o.grid, 7);
  EXPECT_EQ(o.model, ReachModel::QuasiStatic);
  EXPECT_FALSE(o.pid);
  EXPECT_EQ(o.threads, 3);
}

TEST(HandIo, TrackSummaryHasTheResultsFields) {
  TrackOptions o;
  o.target = Vec2(0.2, 0.1);
  o.time = 3;
  const TrackResult r = runTracking(o);
  const nlohmann::json j = trackSummary(r);
  EXPECT_EQ(j["final_error"].get<double>(), r.finalError);
  EXPECT_EQ(j["grasp_held"].get<bool>(), r.graspHeld);
  EXPECT_EQ(j["final_box"][0].get<double>(), r.samples.back().box.x());
  ASSERT_EQ(j["events"].size(), r.events.size());
  EXPECT_EQ(j["events"][0]["what"], r.events[0].what);
}

// A progress callback that throws (Ctrl-C from Python) stops the sweep: the workers finish the
// runs under way, take no new targets, and the exception comes out of runReach.
TEST(HandReach, AProgressThatThrowsStopsTheSweep) {
  ReachOptions o = reachOptions(30, "simulation", false, 2);
  int calls = 0;
  EXPECT_THROW(runReach(o, HandModel{},
                        [&](long, long) {
                          ++calls;
                          throw std::runtime_error("stop");
                        }),
               std::runtime_error);
  EXPECT_EQ(calls, 1);
}

// A law that is the Jacobian controller (a second instance, fresh as the sequence's own after
// begin()) gives the same run, step for step, as the sequence's own controller.
TEST(HandGraspLaw, AnExternalLawEqualToTheControllerGivesTheSameRun) {
  const HandModel model;
  const Vec2 start(-0.1, 0.1), target(0.2, 0.1);
  auto run = [&](bool external) {
    World world(buildHandScene(model), "hand");
    HandGrasp grasp(model, HandControllerParams{});
    EXPECT_TRUE(grasp.attach(world));
    grasp.begin(world, start);
    HandController controller(model);
    int calls = 0;
    const GraspLaw law = [&](const HandJoints& q, const Vec2& box, const HandJoints& commanded) {
      ++calls;
      return controller.update(q, box, target, commanded);
    };
    std::vector<Vec2> path;
    for (int s = 0; s < 180; ++s) {
      grasp.beforeStep(world, external ? std::nullopt : std::optional<Vec2>(target),
                       external ? law : GraspLaw{});
      world.step(world.scene().dt, world.scene().substeps);
      grasp.afterStep(world);
      path.push_back(world.body(grasp.boxBody()).position);
    }
    EXPECT_EQ(calls, external ? grasp.updates() : 0);
    EXPECT_GT(grasp.updates(), 10);
    return path;
  };
  const std::vector<Vec2> own = run(false), external = run(true);
  ASSERT_EQ(own.size(), external.size());
  for (size_t i = 0; i < own.size(); ++i) ASSERT_EQ(own[i], external[i]) << "step " << i;
}

}  // namespace
}  // namespace cablelab
