// Event log: what the engine said during a run (its guards' diagnostics, in its own terms, such
// as "pulley 0 released with a jump"), kept for the Log section of the Inspector
// (ui/log_panel.cpp) rather than shown over the view; the view shows only a plain-words banner
// for what the user caused (ui/plain_words.h).
//
// Needs: the engine's World. No ImGui.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"

namespace cablelab::ui {

struct LogEntry {
  double time = 0;  ///< simulated time when it was taken (s)
  std::string scene;
  std::string text;  ///< the engine's words
};

class EventLog {
 public:
  /// The log keeps the newest this many entries.
  static constexpr size_t kCapacity = 200;

  /// Moves the world's warnings not taken yet into the log and returns them (oldest first).
  std::vector<std::string> take(const World& world, const std::string& scene);
  /// A new world starts: its warnings are counted from the first.
  void newWorld() { seen_ = 0; }
  /// A rewound world replayed warnings the log took the first time: they count as taken.
  void takenAlready(const World& world) { seen_ = world.warnings().size(); }
  const std::deque<LogEntry>& entries() const { return entries_; }
  /// Entries ever added (the panel's "new" count compares against it).
  size_t total() const { return total_; }
  void clear() { entries_.clear(); }

 private:
  std::deque<LogEntry> entries_;
  size_t seen_ = 0, total_ = 0;
};

}  // namespace cablelab::ui
