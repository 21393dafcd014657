#include "ui/turn_target_scenario.h"

#include <cmath>
#include <cstdio>

#include "engine/hand/hand_model.h"
#include "ui/controller_panel.h"
#include "ui/synthetic_events.h"

namespace cablelab::ui {
namespace {

constexpr double kWanted = 0.25;  // rad, where the drag takes the handle
constexpr int kArmPress = 3, kArmDragFrames = 20, kArmRelease = kArmPress + kArmDragFrames + 2;
constexpr double kSettled = 0.02;    // rad: the box within this of the target angle
constexpr double kSettledFor = 1.0;  // s
constexpr int kLastFrame = 3000;

}  // namespace

bool TurnTargetScenario::beforeFrame(Sandbox& sandbox, int frame, std::string& report) {
  World& world = *sandbox.world();
  const int box = world.findBody(kHandBoxName);
  HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  auto fail = [&](const char* why) {
    report = std::string("{\"scenario\": \"turn-target\", \"failure\": \"") + why + "\"}";
    return false;
  };
  if (box < 0 || !h) return fail("not the hand scene");
  if (frame < kArmPress) return true;
  if (frame == kArmPress) {
    const std::optional<Vec2> handle = targetAngleHandle(sandbox);
    if (!handle) return fail("no angle handle (is the box allowed to turn? --set turn=1)");
    sandbox.paused = false;
    from_ = sandbox.camera.toScreen(*handle);
    // The handle's end at kWanted, the same arm's length from the target.
    const Vec2 centre = sandbox.camera.toScreen(*sandbox.target);
    const double arm = (from_ - centre).norm();
    to_ = centre + arm * Vec2(std::cos(kWanted), -std::sin(kWanted));  // screen y points down
    pushMouseEvent(windowId_, SDL_MOUSEMOTION, from_);
    pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, from_);
  } else if (frame <= kArmPress + kArmDragFrames) {
    const double s = double(frame - kArmPress) / kArmDragFrames;
    pushMouseEvent(windowId_, SDL_MOUSEMOTION, from_ + s * (to_ - from_));
  } else if (frame == kArmRelease) {
    pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, to_);
  } else if (frame > kArmRelease) {
    dragged_ = h->targetAngle;
    const double error = std::abs(world.body(box).angle - dragged_);
    if (error > kSettled)
      settledAt_ = -1;
    else if (settledAt_ < 0)
      settledAt_ = world.time();
    const bool settled = settledAt_ >= 0 && world.time() - settledAt_ >= kSettledFor;
    if (settled || frame >= kLastFrame) {
      char text[400];
      std::snprintf(text, sizeof text,
                    "{\"scenario\": \"turn-target\", \"wanted\": %.17g, \"target_angle\": %.17g, "
                    "\"box_angle\": %.17g, \"settled\": %s, \"time\": %.17g, \"frames\": %d, "
                    "\"handle_from\": [%.17g, %.17g], \"handle_to\": [%.17g, %.17g]}",
                    kWanted, dragged_, world.body(box).angle, settled ? "true" : "false",
                    world.time(), frame, from_.x(), from_.y(), to_.x(), to_.y());
      report = text;
      return false;
    }
  }
  return true;
}

}  // namespace cablelab::ui
