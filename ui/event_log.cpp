#include "ui/event_log.h"

namespace cablelab::ui {

std::vector<std::string> EventLog::take(const World& world, const std::string& scene) {
  const auto& warnings = world.warnings();
  if (seen_ > warnings.size()) seen_ = 0;  // a world that was rebuilt behind the log's back
  std::vector<std::string> fresh(warnings.begin() + static_cast<long>(seen_), warnings.end());
  seen_ = warnings.size();
  for (const std::string& w : fresh) {
    entries_.push_back({world.time(), scene, w});
    ++total_;
    if (entries_.size() > kCapacity) entries_.pop_front();
  }
  return fresh;
}

}  // namespace cablelab::ui
