// The sandbox's rewind (ui/timeline.h).
#include "ui/timeline.h"

#include <algorithm>

#include "engine/dynamics/world.h"
#include "engine/dynamics/world_rewind.h"
#include "engine/dynamics/world_state.h"
#include "ui/controller_panel.h"
#include "ui/sandbox.h"

namespace cablelab::ui {

/// What of the hand controller (controller_panel.h) steers the next step.
struct HandFrame {
  HandGrasp grasp;
  bool enabled = true;
  BoxPrediction prediction;
  double predictionTime = -1;
  int seenUpdates = 0;
  double rampStart = -1;
  Vec2 rampFrom = Vec2::Zero(), rampTo = Vec2::Zero();
  std::optional<Vec2> rampLast;
};

namespace {

std::shared_ptr<const HandFrame> handFrame(const Sandbox& sandbox) {
  const HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  if (!h || !h->grasp) return nullptr;
  return std::make_shared<HandFrame>(HandFrame{*h->grasp, h->enabled, h->prediction,
                                               h->predictionTime, h->seenUpdates, h->rampStart,
                                               h->rampFrom, h->rampTo, h->rampLast});
}

void restoreHand(Sandbox& sandbox, const HandFrame& f) {
  HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  if (!h) return;
  h->grasp = std::make_unique<HandGrasp>(f.grasp);
  h->enabled = f.enabled;
  h->prediction = f.prediction;
  h->predictionTime = f.predictionTime;
  h->seenUpdates = f.seenUpdates;
  h->rampStart = f.rampStart;
  h->rampFrom = f.rampFrom;
  h->rampTo = f.rampTo;
  h->rampLast = f.rampLast;
}

/// The inputs that take a world at history `from` to history `to` (`from` a prefix of `to`, but
/// for the count of its last run of steps); nullopt if `from` is not such a prefix.
std::optional<std::vector<WorldInput>> inputsBetween(const std::vector<WorldInput>& from,
                                                     const std::vector<WorldInput>& to) {
  if (from.empty() || from.size() > to.size()) return std::nullopt;
  const size_t last = from.size() - 1;
  for (size_t k = 0; k < last; ++k)
    if (from[k].kind != to[k].kind || from[k].index != to[k].index ||
        from[k].count != to[k].count || from[k].values != to[k].values)
      return std::nullopt;
  const WorldInput &a = from[last], &b = to[last];
  if (a.kind != b.kind || a.index != b.index || a.values != b.values || a.count > b.count)
    return std::nullopt;
  if (a.kind != WorldInput::Kind::Step && a.count != b.count) return std::nullopt;
  std::vector<WorldInput> rest;
  if (b.count > a.count) rest.push_back({b.kind, b.index, b.count - a.count, b.values});
  rest.insert(rest.end(), to.begin() + static_cast<long>(from.size()), to.end());
  return rest;
}

}  // namespace

void Timeline::clear() {
  frames_.clear();
  current_ = -1;
  run_.clear();
}

void Timeline::record(const Sandbox& sandbox) {
  const World* world = sandbox.world();
  if (!world) return;
  // A step from a restored moment: the old run's later frames are gone.
  while (!frames_.empty() && frames_.back().step >= world->stepCount()) frames_.pop_back();
  run_.clear();
  frames_.push_back({world->stepCount(), world->time(), sandbox.target, handFrame(sandbox)});
  while (frames_.size() > 1 && frames_.back().time - frames_.front().time > kKeptSeconds + 1e-9)
    frames_.pop_front();
  current_ = frameCount() - 1;
}

int Timeline::frameAt(double time) const {
  const auto after = std::upper_bound(frames_.begin(), frames_.end(), time,
                                      [](double t, const TimelineFrame& f) { return t < f.time; });
  return std::max(0, static_cast<int>(after - frames_.begin()) - 1);
}

bool Timeline::rewindTo(Sandbox& sandbox, int i) {
  const World* world = sandbox.world();
  if (!world || i < 0 || i >= frameCount()) return false;
  sandbox.paused = true;
  sandbox.pendingSteps = 0;
  if (i == current_ && world->stepCount() == frames_[i].step) return true;
  if (run_.empty()) run_ = world->history().inputs();
  try {
    const std::vector<WorldInput> wanted = inputsThroughStep(run_, frames_[i].step);
    // Forward within the run, nothing edited since: play the world on (cheaper than a rebuild).
    const auto rest =
        i > current_ ? inputsBetween(world->history().inputs(), wanted) : std::nullopt;
    std::unique_ptr<World> rebuilt;
    if (rest) {
      replayInputs(*sandbox.world(), *rest, sandbox.sceneName);
    } else {
      rebuilt = std::make_unique<World>(world->scene(), sandbox.sceneName);
      replayInputs(*rebuilt, wanted, sandbox.sceneName);
    }
    sandbox.adoptRewound(std::move(rebuilt));
  } catch (const std::exception& e) {
    sandbox.error = std::string("cannot go back to that moment: ") + e.what();
    return false;
  }
  sandbox.target = frames_[i].target;
  if (frames_[i].hand) restoreHand(sandbox, *frames_[i].hand);
  current_ = i;
  return true;
}

bool Timeline::stepBack(Sandbox& sandbox) {
  if (current_ <= 0) return false;
  return rewindTo(sandbox, current_ - 1);
}

size_t Timeline::bytes() const {
  size_t n =
      sizeof(*this) + frames_.size() * sizeof(TimelineFrame) + run_.capacity() * sizeof(WorldInput);
  for (const TimelineFrame& f : frames_)
    if (f.hand) {
      n += sizeof(HandFrame);
      for (const GraspEvent& e : f.hand->grasp.events())
        n += sizeof(GraspEvent) + e.what.capacity();
    }
  return n;
}

void timelineAfterStep(Sandbox& sandbox) {
  if (sandbox.timeline) sandbox.timeline->record(sandbox);
}

}  // namespace cablelab::ui
