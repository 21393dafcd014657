// The sandbox's rewind (ui/timeline.h) without a window: a run recorded step by step, rewound to
// an earlier moment and played on, moves exactly as it did (bit for bit), with the hand's grasp
// sequence and controller steering it; the last 30 s are kept and no more.
#include "ui/timeline.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <vector>

#include "tests/support/body_states.h"
#include "ui/controller_panel.h"
#include "ui/sandbox.h"

namespace cablelab::ui {
namespace timeline_test {  // named: unity batches join test files

/// `steps` fixed steps, the poses after each.
std::vector<std::vector<double>> run(Sandbox& sandbox, int steps) {
  std::vector<std::vector<double>> out;
  for (int i = 0; i < steps; ++i) {
    sandbox.advance(sandbox.dt, true);
    out.push_back(test::bodyStates(*sandbox.world()));
  }
  return out;
}

// The hand's grasp sequence and outer loop steer the world from outside it (servo targets from
// the controller's state): a rewound moment must bring that state back too.
TEST(Timeline, TheHandPlaysOnFromARewoundMomentBitForBit) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hand"));
  sandbox.target = Vec2(0.1, 0.05);
  ASSERT_TRUE(startHandGrasp(sandbox));
  // A drag before the moment (forces recorded in the world's history), then none.
  const int box = sandbox.controller->hand->box();
  auto before = run(sandbox, 40);
  sandbox.beginDrag(box, sandbox.world()->body(box).position);
  sandbox.dragTo(sandbox.world()->body(box).position + Vec2(0.02, 0.01));
  auto dragged = run(sandbox, 20);
  sandbox.endDrag();
  auto after = run(sandbox, 180);  // 4 s: closing, settling, the outer loop running
  std::vector<std::vector<double>> recorded = before;
  recorded.insert(recorded.end(), dragged.begin(), dragged.end());
  recorded.insert(recorded.end(), after.begin(), after.end());
  ASSERT_EQ(sandbox.timeline->frameCount(), 240);
  EXPECT_EQ(handGraspState(sandbox), "grasped");

  constexpr int kMoment = 99;  // step 100, after the drag
  const int updatesAtEnd = sandbox.controller->hand->grasp->updates();
  ASSERT_TRUE(sandbox.timeline->rewindTo(sandbox, kMoment));
  EXPECT_TRUE(sandbox.paused);
  EXPECT_TRUE(sandbox.timeline->rewound());
  EXPECT_EQ(sandbox.world()->stepCount(), sandbox.timeline->frame(kMoment).step);
  ASSERT_EQ(test::bodyStates(*sandbox.world()), recorded[kMoment]);
  const int updatesThen = sandbox.controller->hand->grasp->updates();
  sandbox.paused = false;
  const auto replay = run(sandbox, 240 - kMoment - 1);
  for (size_t k = 0; k < replay.size(); ++k)
    ASSERT_EQ(replay[k], recorded[kMoment + 1 + k]) << "step " << kMoment + 2 + k;
  EXPECT_EQ(handGraspState(sandbox), "grasped");
  // The controller came back as it was at the moment (its outer loop's count), then ran on.
  EXPECT_LT(updatesThen, updatesAtEnd);
  EXPECT_EQ(sandbox.controller->hand->grasp->updates(), updatesAtEnd);
  EXPECT_FALSE(sandbox.timeline->rewound());
  EXPECT_EQ(sandbox.timeline->frameCount(), 240);
}

// Back one step at a time, then forward along the same run (played on, not rebuilt), then a
// different input from the rewound moment: a new run, the old one's later frames dropped.
TEST(Timeline, StepBackForwardAndANewRunFromTheMoment) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("pulley"));
  const auto recorded = run(sandbox, 90);
  Timeline& t = *sandbox.timeline;
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(t.stepBack(sandbox));
  EXPECT_EQ(t.current(), 86);
  EXPECT_EQ(test::bodyStates(*sandbox.world()), recorded[86]);
  ASSERT_TRUE(t.rewindTo(sandbox, 30));
  EXPECT_EQ(test::bodyStates(*sandbox.world()), recorded[30]);
  const World* rebuilt = sandbox.world();
  ASSERT_TRUE(t.rewindTo(sandbox, 60));  // forward: the same World object, stepped on
  EXPECT_EQ(sandbox.world(), rebuilt);
  EXPECT_EQ(test::bodyStates(*sandbox.world()), recorded[60]);
  ASSERT_TRUE(t.rewindTo(sandbox, 89));
  EXPECT_EQ(test::bodyStates(*sandbox.world()), recorded[89]);
  EXPECT_FALSE(t.rewound());

  ASSERT_TRUE(t.rewindTo(sandbox, 50));
  sandbox.gravity = Vec2(0, -3);  // a different run from step 51 on
  sandbox.paused = false;
  run(sandbox, 5);
  EXPECT_EQ(t.frameCount(), 56);
  EXPECT_NE(test::bodyStates(*sandbox.world()), recorded[55]);
  ASSERT_TRUE(t.stepBack(sandbox));  // back into the new run, not the old one
  EXPECT_EQ(sandbox.world()->stepCount(), 55);
  EXPECT_DOUBLE_EQ(sandbox.world()->gravity().y(), -3);
}

// 30 s kept behind the newest frame, and the oldest one still restores exactly. The figure for
// 30 s of the hand (the README's) is printed.
TEST(Timeline, KeepsTheLastThirtySecondsAndTheOldestRestores) {
  Sandbox sandbox(800, 600);
  ASSERT_TRUE(sandbox.open("hand"));
  const int steps = static_cast<int>(std::lround(33.0 / sandbox.dt));
  const auto recorded = run(sandbox, steps);
  const Timeline& t = *sandbox.timeline;
  const double kept = t.frame(t.frameCount() - 1).time - t.frame(0).time;
  EXPECT_LE(kept, Timeline::kKeptSeconds);
  EXPECT_GE(kept, Timeline::kKeptSeconds - 2 * sandbox.dt);
  const int oldest = steps - t.frameCount();  // index into `recorded`
  EXPECT_EQ(t.frame(0).step, oldest + 1);
  const size_t bytes = t.bytes();
  std::printf("30 s of the hand: %d frames, %.2f MB\n", t.frameCount(), bytes / 1048576.0);
  EXPECT_LT(bytes, 8u << 20);

  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(sandbox.timeline->rewindTo(sandbox, 0));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("rewinding 33 s of the hand to its oldest kept moment: %.0f ms\n", 1e3 * seconds);
  EXPECT_EQ(test::bodyStates(*sandbox.world()), recorded[oldest]);
}

}  // namespace timeline_test
}  // namespace cablelab::ui
