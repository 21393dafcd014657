// Plain words (ui/plain_words.h) and the sandbox's banner and log (ui/sandbox.h, ui/event_log.h):
// the user's drag that overstretches a cable gets one sentence for students; the engine's own
// diagnostics never reach the view.
#include "ui/plain_words.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "ui/sandbox.h"

namespace cablelab::ui {
namespace plain_words_test {  // named: unity batches join test files

// Words a student should not meet on the view (the engine's and the solver's).
const char* const kSolverWords[] = {"guard",    "t = ", "sub-step",   "rest length",
                                    "pulley 0", "jump", "constraint", "solve"};

const std::string kOverstretch =
    "cable 'rope': rigid and 0.0213 m longer than its rest length at t = 1.25 s: the step did "
    "not resolve the motion (a fast turn or impact); more sub-steps hold it";
const std::string kJump =
    "cable 'top_membrane': pulley 0 released with a jump of -0.743858 m at t = 0.5 s";

TEST(PlainWords, TheUsersDragGetsOnePlainSentence) {
  const std::string s = plainBanner(kOverstretch, {UserAction::Kind::Drag, "weight"});
  EXPECT_NE(s.find("'weight'"), std::string::npos) << s;
  EXPECT_NE(s.find("'rope'"), std::string::npos) << s;
  EXPECT_NE(s.find("Let go"), std::string::npos) << s;
  for (const char* w : kSolverWords) EXPECT_EQ(s.find(w), std::string::npos) << w << " in " << s;
}

TEST(PlainWords, EngineDiagnosticsAndScenesOwnMotionRaiseNoBanner) {
  EXPECT_EQ(plainBanner(kJump, {UserAction::Kind::Drag, "box"}), "");
  EXPECT_EQ(plainBanner(kOverstretch, {}), "") << "no user action: the log only";
  EXPECT_NE(plainBanner(kOverstretch, {UserAction::Kind::CableEdit, ""}), "");
}

// In the sandbox: a hard drag of the hexagon's weight (a "what to try" step) raises no banner;
// a cable edit that leaves the rope far too long for its new rest length logs the engine's words
// and shows the plain banner, never the engine's words.
TEST(PlainWords, SandboxLogsEveryWarningAndBannersOnlyTheUsers) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hexagon"));
  World& world = *sandbox.world();
  const int weight = world.findBody("weight");
  ASSERT_GE(weight, 0);
  sandbox.dragWeights = 20;
  sandbox.beginDrag(weight, world.body(weight).position);
  sandbox.dragTo(world.body(weight).position + Vec2(1, -2));
  for (int i = 0; i < 60; ++i) sandbox.advance(sandbox.dt, true);
  sandbox.endDrag();
  EXPECT_EQ(sandbox.banner, "") << "a drag within the scene's means is no warning";
  // The rope's rest length cut by half while it runs: the engine reports it overstretched.
  sandbox.selectedCable = 0;
  sandbox.cableEdit.restLength = 0.5 * world.cable(0).restLength();
  ASSERT_TRUE(sandbox.applyCableEdit());
  for (int i = 0; i < 10; ++i) sandbox.advance(sandbox.dt, true);
  ASSERT_FALSE(sandbox.log.entries().empty()) << "the edit should overstretch the rope";
  EXPECT_NE(sandbox.banner.find("After your change"), std::string::npos) << sandbox.banner;
  for (const char* w : kSolverWords)
    EXPECT_EQ(sandbox.banner.find(w), std::string::npos) << w << " in " << sandbox.banner;
  // The log keeps the engine's words, with the scene.
  const auto& log = sandbox.log.entries();
  EXPECT_TRUE(std::any_of(log.begin(), log.end(), [](const LogEntry& e) {
    return e.text.find("longer than its rest length") != std::string::npos && e.scene == "hexagon";
  }));
}

// The status line's energy: the ballast come to rest read "energy 1.421e-14 J".
TEST(PlainWords, EnergyAtRestReadsZero) {
  EXPECT_EQ(energyReadout(1.4210854715202004e-14), "0");
  EXPECT_EQ(energyReadout(-3e-12), "0");
  EXPECT_EQ(energyReadout(-0.005241), "-0.005241");
  EXPECT_EQ(energyReadout(470.61), "470.6");
  EXPECT_EQ(energyReadout(4.5), "4.5");
}

}  // namespace plain_words_test
}  // namespace cablelab::ui
