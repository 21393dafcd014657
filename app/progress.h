// The one progress bar of the commands that run long (reach, track, run, record, bench):
//   reach [############------------------]  40%  10/25  eta 3 s
// on stderr, redrawn in place, and only when stderr is a terminal: a pipe, a file or a test
// capturing stderr sees nothing (docs/cli.md, "Progress").
#pragma once

#include <chrono>
#include <string>

namespace cablelab::app {

class Progress {
 public:
  /// `total` units of work (steps, targets, frames, stages).
  Progress(std::string label, long total);
  /// Ends a bar left open by an error, so that the error message starts on its own line.
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// `done` of the total units are finished; `note` says what runs now (may be empty). Draws at
  /// most ten times a second, and only once the run has lasted half a second.
  void update(long done, const std::string& note = {});
  /// The run finished: the full bar with the elapsed time, then a newline (if a bar was shown).
  void done();

 private:
  using Clock = std::chrono::steady_clock;
  void draw(long done, const std::string& tail);

  std::string label_, note_;
  long total_;
  bool terminal_;
  bool shown_ = false, finished_ = false;
  Clock::time_point start_, lastDraw_;
};

}  // namespace cablelab::app
