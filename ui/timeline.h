// Timeline: the sandbox's rewind. The last 30 s of simulated time are kept, one frame per step;
// the Timeline section's slider and the step-back key (b) put the world back at any of them, and
// playing on from there repeats the run's motion bit for bit (the same inputs, the same state).
//
// A World's contact and solver caches cannot be copied out, so a moment is restored the one
// bit-exact way (engine/dynamics/world_rewind.h): the scene rebuilt and the run's input history
// replayed through that step. What lives outside the World and steers it is kept per frame: the
// controller target and the hand's grasp sequence (a copy of its state). Stepping a restored
// world starts a new run from that moment: the frames after it are dropped.
//
// Needs: ui/sandbox.h, ui/controller_panel.h (the hand's state). No SDL, no GL.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "engine/core/math.h"
#include "engine/dynamics/world_history.h"

namespace cablelab::ui {

class Sandbox;
struct HandFrame;  // timeline.cpp: the hand controller's state after a step

/// One kept moment: the state right after a step.
struct TimelineFrame {
  long step = 0;                          ///< World::stepCount()
  double time = 0;                        ///< s
  std::optional<Vec2> target;             ///< the controller target (m)
  std::shared_ptr<const HandFrame> hand;  ///< null: no hand controller
};

class Timeline {
 public:
  static constexpr double kKeptSeconds = 30;  ///< simulated time kept behind the newest frame

  /// Forgets every frame (a new scene, a reset).
  void clear();
  /// Records the sandbox's moment after a step. A step from a restored moment drops the
  /// frames after it (a new run starts there).
  void record(const Sandbox& sandbox);

  int frameCount() const { return static_cast<int>(frames_.size()); }
  const TimelineFrame& frame(int i) const { return frames_[i]; }
  /// The frame the world shows: frameCount() - 1 unless rewound.
  int current() const { return current_; }
  bool rewound() const { return current_ + 1 < frameCount(); }
  /// The newest frame at or before `time` (s), 0 if none is.
  int frameAt(double time) const;

  /// Puts the sandbox's world and controller back at frame `i` (pauses). False (the sandbox
  /// unchanged, `sandbox.error` set) if the replay fails.
  bool rewindTo(Sandbox& sandbox, int i);
  /// One step back (pauses); false at the oldest frame.
  bool stepBack(Sandbox& sandbox);

  /// Bytes held: frames, the hand's copies and the run's input history kept while rewound.
  size_t bytes() const;

 private:
  std::deque<TimelineFrame> frames_;
  int current_ = -1;
  /// While rewound: the history of the run being scrubbed (the world's own stops at `current_`).
  std::vector<WorldInput> run_;
};

/// Records the sandbox's moment in its timeline (Sandbox::afterStep calls it).
void timelineAfterStep(Sandbox& sandbox);

}  // namespace cablelab::ui
