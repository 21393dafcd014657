// The sandbox's controller hook (ui/controller_panel.cpp) without a window: the hand's grasp
// sequence and Jacobian controller against `cablelab track`, the statics prediction overlay,
// and the membrane scene's model force arrow and fit-parameter loading.
#include "ui/controller_panel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/membrane/membrane_model.h"
#include "tests/ui/test_support.h"

namespace cablelab::ui {
namespace {

constexpr double kSameAsTrack = 1e-9;  // m: the same steps in the same order

void runFor(Sandbox& sandbox, double seconds) {
  const long steps = std::lround(seconds / sandbox.dt);
  for (long i = 0; i < steps; ++i) sandbox.advance(sandbox.dt, true);
}

TEST(ControllerPanel, HandOpensPinchedWithATargetAndAPrediction) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hand"));
  ASSERT_TRUE(sandbox.controller && sandbox.controller->hand);
  ASSERT_TRUE(sandbox.target.has_value());
  runFor(sandbox, 1.0);
  const HandControlState& h = *sandbox.controller->hand;
  EXPECT_GT(h.grasp->updates(), 5);  // the outer loop runs after the settle time
  ASSERT_TRUE(h.prediction.valid);
  const Overlay o = sandbox.overlay();
  ASSERT_EQ(o.targets.size(), 2u);  // the target and the statics prediction
  EXPECT_NEAR((o.targets[1].position - h.prediction.box).norm(), 0, 1e-12);
  EXPECT_GT(h.history.count, 50);
}

// The panel runs the engine's grasp sequence (HandGrasp), so its run is `cablelab track`'s to the
// bit: the same grasp time, the same box and the same events.
TEST(ControllerPanel, GraspSequenceMatchesCablelabTrack) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hand"));
  sandbox.target = Vec2(0.1, 0.05);
  ASSERT_TRUE(startHandGrasp(sandbox));
  runFor(sandbox, 4.0);
  const HandControlState& h = *sandbox.controller->hand;
  ASSERT_GE(h.grasp->graspTime(), 0);
  EXPECT_EQ(handGraspState(sandbox), "grasped");
  const Vec2 box = sandbox.world()->body(h.box()).position;

  const auto r =
      test::run(std::string(CABLELAB_CLI) + " track --target 0.1,0.05 --time 4", "track");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(h.grasp->graspTime(), j["grasp_time"].get<double>(), 1e-9);
  EXPECT_EQ(h.grasp->losses(), j["losses"].get<int>());
  EXPECT_NEAR((box - Vec2(0.1, 0.05)).norm(), j["final_error"].get<double>(), kSameAsTrack);
  EXPECT_NEAR(box.x(), j["final_box"][0].get<double>(), kSameAsTrack);
  EXPECT_NEAR(box.y(), j["final_box"][1].get<double>(), kSameAsTrack);
  ASSERT_EQ(h.grasp->events().size(), j["events"].size());
  for (size_t k = 0; k < j["events"].size(); ++k)
    EXPECT_EQ(h.grasp->events()[k].what, j["events"][k]["what"].get<std::string>());
}

// "Plan ahead" runs the engine's MPC the way `cablelab track --controller mpc` does (the same
// box to the bit), and the choice survives the reset the grasp starts with.
TEST(ControllerPanel, PlanAheadIsTrackControllerMpc) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hand"));
  sandbox.controller->hand->setLaw(HandLaw::Mpc, 4);
  sandbox.target = Vec2(0.1, 0.05);
  ASSERT_TRUE(startHandGrasp(sandbox));
  runFor(sandbox, 3.0);
  const HandControlState& h = *sandbox.controller->hand;
  ASSERT_EQ(h.law, HandLaw::Mpc);
  EXPECT_TRUE(h.mpc->status().planned);
  EXPECT_EQ(h.mpc->params().horizon, 4);
  const Vec2 box = sandbox.world()->body(h.box()).position;
  const auto r = test::run(
      std::string(CABLELAB_CLI) + " track --target 0.1,0.05 --time 3 --controller mpc --horizon 4",
      "track_mpc");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(box.x(), j["final_box"][0].get<double>(), kSameAsTrack);
  EXPECT_NEAR(box.y(), j["final_box"][1].get<double>(), kSameAsTrack);
  // The Jacobian controller's run differs (the law was wired in, not just shown).
  const auto pd =
      test::run(std::string(CABLELAB_CLI) + " track --target 0.1,0.05 --time 3", "track_pd");
  const auto k = nlohmann::json::parse(pd.out);
  EXPECT_GT((box - Vec2(k["final_box"][0].get<double>(), k["final_box"][1].get<double>())).norm(),
            1e-4);
}

// A box pulled out of the membranes is the engine's grasp loss: the panel's state says so, with
// the engine's reason, and the hand stops, then tries to grasp again.
TEST(ControllerPanel, ABoxPulledOutIsTheEnginesGraspLoss) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hand"));
  runFor(sandbox, 1.0);
  EXPECT_EQ(handGraspState(sandbox), "pinch pose");
  const HandControlState& h = *sandbox.controller->hand;
  sandbox.dragWeights = 20;
  const Vec2 box = sandbox.world()->body(h.box()).position;
  sandbox.beginDrag(h.box(), box);
  sandbox.dragTo(box + Vec2(1.5, 0));
  runFor(sandbox, 1.0);
  sandbox.endDrag();
  EXPECT_EQ(handGraspState(sandbox), "grasp lost");
  ASSERT_GE(h.grasp->losses(), 1);
  const auto& events = h.grasp->events();
  const bool engineReason = std::any_of(events.begin(), events.end(), [](const GraspEvent& e) {
    return e.what == "top membrane unwrapped" || e.what == "bottom membrane unwrapped" ||
           e.what == "top membrane slack" || e.what == "bottom membrane slack";
  });
  EXPECT_TRUE(engineReason);
  EXPECT_FALSE(h.grasp->held());
}

TEST(ControllerPanel, GainsSurviveAResetAndPidUsesKi) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hand"));
  HandControlState& h = *sandbox.controller->hand;
  h.params.kp = 0.2;
  h.pid = true;
  h.ki = 0.05;
  h.applyGains();
  EXPECT_DOUBLE_EQ(h.controller().params().ki, 0.05);
  sandbox.reset();
  const HandControlState& fresh = *sandbox.controller->hand;
  EXPECT_DOUBLE_EQ(fresh.controller().params().kp, 0.2);
  EXPECT_DOUBLE_EQ(fresh.controller().params().ki, 0.05);
}

TEST(ControllerPanel, MembraneShowsTheModelForceAndLoadsFitParameters) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("membrane"));
  ASSERT_TRUE(sandbox.controller && sandbox.controller->membrane);
  runFor(sandbox, 0.5);
  const World& world = *sandbox.world();
  const int band = sandbox.controller->membrane->band;
  const CableDef& def = world.cable(band).def();
  const Vec2 p = world.body(sandbox.controller->membrane->finger).position;
  const MembraneGeometry g{def.start.point, def.end.point};
  const Vec2 f = membraneForce(g, {world.cable(band).stiffness(), world.cable(band).preload()}, p);
  const Overlay o = sandbox.overlay();
  ASSERT_EQ(o.arrows.size(), 1u);
  const Vec2 drawn = o.arrows[0].to - o.arrows[0].from;
  EXPECT_NEAR((o.arrows[0].from - p).norm(), 0, 1e-12);
  EXPECT_NEAR(drawn.normalized().dot(f.normalized()), 1, 1e-9);

  const auto dir = test::outputDir("controller");
  const std::string good = (dir / "fit.json").string(), bad = (dir / "bad.json").string();
  std::ofstream(good) << R"({"k": 31.5, "preload": 0.25, "rms_fy": 0.1})";
  std::ofstream(bad) << R"({"k": -1, "preload": 0.25})";
  const MembraneParams loaded = loadFitParameters(good);
  EXPECT_DOUBLE_EQ(loaded.k, 31.5);
  EXPECT_DOUBLE_EQ(loaded.preload, 0.25);
  EXPECT_THROW(loadFitParameters(bad), InputError);
  EXPECT_THROW(loadFitParameters((dir / "missing.json").string()), InputError);

  std::string message;
  EXPECT_FALSE(loadFitIntoBand(sandbox, bad, message));
  EXPECT_NE(message.find("bad.json"), std::string::npos) << message;
  ASSERT_TRUE(loadFitIntoBand(sandbox, good, message)) << message;
  const Cable& cable = sandbox.world()->cable(band);
  EXPECT_DOUBLE_EQ(cable.stiffness(), 31.5);
  EXPECT_DOUBLE_EQ(cable.preload(), 0.25);
  EXPECT_DOUBLE_EQ(cable.restLength(), (g.b - g.a).norm());
}

}  // namespace
}  // namespace cablelab::ui
