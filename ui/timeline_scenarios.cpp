// The rewind and plot scenarios (ui/timeline_scenarios.h).
#include "ui/timeline_scenarios.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "ui/controller_panel.h"
#include "ui/input.h"
#include "ui/plot_board.h"
#include "ui/plot_panel.h"
#include "ui/report_json.h"
#include "ui/synthetic_events.h"
#include "ui/timeline.h"

namespace cablelab::ui {
namespace {

constexpr int kRecorded = 150, kBack = 30, kReplay = 60;
constexpr double kFarSeconds = 0.5, kNearSeconds = 2.3;

std::vector<double> poses(const World& w) {
  std::vector<double> out;
  for (int i = 0; i < w.bodyCount(); ++i) {
    const BodyState& s = w.body(i);
    out.insert(out.end(), {s.position.x(), s.position.y(), s.angle});
  }
  return out;
}

bool helpListsStepBack() {
  for (int k = 0; kShortcuts[k][0]; ++k)
    if (std::strcmp(kShortcuts[k][0], "b") == 0) return true;
  return false;
}

}  // namespace

const std::vector<std::string>& TimelineScenario::names() {
  static const std::vector<std::string> n = {"rewind", "plot-export"};
  return n;
}

TimelineScenario::TimelineScenario(std::string name, Uint32 windowId, std::string out)
    : name_(std::move(name)), out_(std::move(out)), windowId_(windowId) {}

bool TimelineScenario::beforeFrame(Sandbox& sandbox, int frame, std::string& report) {
  if (!sandbox.controller || !sandbox.controller->hand) {
    report = "{\"scenario\": \"" + name_ + "\", \"failure\": \"not the hand scene\"}";
    return false;
  }
  return name_ == "rewind" ? rewind(sandbox, frame, report) : plotExport(sandbox, frame, report);
}

// One step per frame (scripted runs use fixed steps): at frame f the world has taken f steps
// unless paused.
bool TimelineScenario::rewind(Sandbox& sandbox, int frame, std::string& report) {
  const World& world = *sandbox.world();
  const int box = sandbox.controller->hand->box();
  if (frame == 1) sandbox.target = world.body(box).position + Vec2(0.04, 0.03);  // a click
  const long step = world.stepCount();
  if (frame <= kRecorded) {
    recorded_.resize(step + 1);
    recorded_[step] = poses(world);
  }
  if (frame >= kRecorded && frame < kRecorded + kBack) pushKeyPress(windowId_, SDLK_b);
  if (frame == kRecorded + kBack) {
    stepAfterBack_ = step;
    equalAfterBack_ =
        step >= 0 && step < static_cast<long>(recorded_.size()) && poses(world) == recorded_[step];
    pushKeyPress(windowId_, SDLK_SPACE);
  }
  if (frame > kRecorded + kBack && step < static_cast<long>(recorded_.size())) {
    const auto now = poses(world);
    for (size_t k = 0; k < now.size(); ++k)
      largest_ = std::max(largest_, std::abs(now[k] - recorded_[step][k]));
    ++compared_;
  }
  if (frame == kRecorded + kBack + kReplay) pushKeyPress(windowId_, SDLK_b);
  if (frame < kRecorded + kBack + kReplay + 2) return true;
  const Timeline& t = *sandbox.timeline;
  report = "{\"scenario\": \"rewind\", \"recorded\": " + std::to_string(kRecorded) +
           ", \"back\": " + std::to_string(kBack) +
           ", \"step_after_back\": " + std::to_string(stepAfterBack_) +
           ", \"equal_after_back\": " + (equalAfterBack_ ? "true" : "false") +
           ", \"compared\": " + std::to_string(compared_) +
           ", \"largest_difference\": " + jsonNumber(largest_) +
           ", \"paused\": " + (sandbox.paused ? "true" : "false") +
           ", \"rewound\": " + (t.rewound() ? "true" : "false") +
           ", \"frames\": " + std::to_string(t.frameCount()) +
           ", \"bytes\": " + std::to_string(t.bytes()) +
           ", \"help_has_b\": " + (helpListsStepBack() ? "true" : "false") + "}";
  return false;
}

bool TimelineScenario::plotExport(Sandbox& sandbox, int frame, std::string& report) {
  const World& world = *sandbox.world();
  PlotBoard& board = *sandbox.plots;
  const int box = sandbox.controller->hand->box();
  const HandGrasp& grasp = *sandbox.controller->hand->grasp;
  const int farFrames = static_cast<int>(std::lround(kFarSeconds / sandbox.dt));
  const int nearFrames = static_cast<int>(std::lround(kNearSeconds / sandbox.dt));
  if (frame == 1) {
    board.windowSeconds = 2;
    board.addCurve(0, {Quantity::Kind::ControllerError, -1, 0});
    board.addCurve(1, {Quantity::Kind::X, box, 0});
    board.addCurve(1, {Quantity::Kind::Y, box, 0});
    board.addCurve(2, {Quantity::Kind::Tension, grasp.membrane(0), 0});
    board.addCurve(2, {Quantity::Kind::Tension, grasp.membrane(1), 0});
    sandbox.target = world.body(box).position + Vec2(3, 4);  // 5 m away
  }
  if (frame == 1 + farFrames) {
    const auto r = board.valueRange(board.charts[0], world.time());
    rangeFar_[0] = r[0], rangeFar_[1] = r[1];
    sandbox.target = world.body(box).position + Vec2(0.02, 0);
  }
  if (frame < 1 + farFrames + nearFrames) return true;
  const auto after = board.valueRange(board.charts[0], world.time());
  std::string files;
  try {
    for (size_t i = 0; i < board.charts.size(); ++i) {
      const std::string stem = out_ + "-" + std::to_string(i);
      exportChart(sandbox, i, stem, 1600, 900);
      files += std::string(i ? ", " : "") + "\"" + stem + "\"";
    }
  } catch (const std::exception& e) {
    report = "{\"scenario\": \"plot-export\", \"failure\": \"" + std::string(e.what()) + "\"}";
    return false;
  }
  const auto& t = board.times();
  const auto& error = board.charts[0].values[0];
  report = "{\"scenario\": \"plot-export\", \"range_far\": [" + jsonNumber(rangeFar_[0]) + ", " +
           jsonNumber(rangeFar_[1]) + "], \"range_after\": [" + jsonNumber(after[0]) + ", " +
           jsonNumber(after[1]) + "], \"files\": [" + files +
           "], \"last_time\": " + jsonNumber(t.back()) +
           ", \"last_error\": " + jsonNumber(error.back()) +
           ", \"time\": " + jsonNumber(world.time()) + "}";
  return false;
}

}  // namespace cablelab::ui
