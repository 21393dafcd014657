#include "ui/law_target_scenario.h"

#include <cmath>

#include "engine/hand/hand_model.h"
#include "ui/controller_panel.h"
#include "ui/report_json.h"
#include "ui/synthetic_events.h"

namespace cablelab::ui {

Vec2 LawTargetScenario::centreOf(const PanelRect& r) {
  return Vec2(r.x + 0.5 * r.width, r.y + 0.5 * r.height);
}

void LawTargetScenario::click(const Vec2& screen, int frame, int at) {
  // The pointer itself moves there: Dear ImGui's SDL backend reads its position from SDL's mouse
  // state, which pushed motion events leave alone.
  if (frame == at)
    SDL_WarpMouseInWindow(SDL_GetWindowFromID(windowId_), static_cast<int>(std::lround(screen.x())),
                          static_cast<int>(std::lround(screen.y())));
  if (frame == at) pushMouseEvent(windowId_, SDL_MOUSEMOTION, screen);
  if (frame == at + 1) pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, screen);
  if (frame == at + 2) pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, screen);
}

bool LawTargetScenario::beforeFrame(Sandbox& sandbox, int frame, std::string& report) {
  const World& world = *sandbox.world();
  const int box = world.findBody(kHandBoxName);
  HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  const std::string name = mpc_ ? kMpc : kPid;
  auto fail = [&](const std::string& why) {
    report = "{\"scenario\": " + jsonQuoted(name) + ", \"failure\": " + jsonQuoted(why) + "}";
    return false;
  };
  if (box < 0 || !h) return fail("not the hand scene");
  if (frame == 2) sandbox.paused = false;
  if (frame >= kLawClick && frame < kLawClick + 3) {
    const PanelRect& choice = h->lawRects[mpc_ ? 1 : 0];
    if (choice.width <= 0) return fail("the law's choice is not shown");
    click(centreOf(choice), frame, kLawClick);
  }
  if (!mpc_ && frame >= kPidClick && frame < kPidClick + 3) {  // PID starts off
    if (h->pidRect.width <= 0) return fail("the PID toggle is not shown");
    click(centreOf(h->pidRect), frame, kPidClick);
  }
  if (frame == kTargetClick) {
    target_ = Vec2(kTargetX, 0.0);
    if (sandbox.bodyAt(target_, true) >= 0 ||
        sandbox.cableAt(target_, 6 * sandbox.camera.metresPerPixel) >= 0)
      return fail("the target's point is not empty space");
  }
  if (frame >= kTargetClick && frame < kTargetClick + 3)
    click(sandbox.camera.toScreen(target_), frame, kTargetClick);
  // The click took once the target is where it was clicked (to the pixel).
  if (frame <= kTargetClick + 1 || !sandbox.target ||
      (*sandbox.target - target_).norm() > sandbox.camera.metresPerPixel)
    return frame < kTargetClick + 10 || fail("the click did not set the target");
  const double t = world.time();
  if (clickedAt_ < 0) clickedAt_ = t;
  const double error = (world.body(box).position - *sandbox.target).norm();
  closest_ = std::min(closest_, error);
  if (error >= kWithin)
    enteredAt_ = -1;
  else if (enteredAt_ < 0)
    enteredAt_ = t;
  const bool settled = enteredAt_ >= 0 && t - enteredAt_ >= kSettledFor;
  if (!settled && t - clickedAt_ < kLongestRun) return true;
  report = "{\"scenario\": " + jsonQuoted(name) +
           ", \"law\": " + jsonQuoted(h->law == HandLaw::Mpc ? "mpc" : "jacobian") +
           ", \"pid\": " + (h->pid ? "true" : "false") +
           ", \"horizon\": " + jsonNumber(h->horizon) +
           ", \"planned\": " + (h->mpc->status().planned ? "true" : "false") + ", \"target\": [" +
           jsonNumber(target_.x()) + ", " + jsonNumber(target_.y()) +
           "], \"settled\": " + (settled ? "true" : "false") +
           ", \"time_to_5mm\": " + jsonNumber(settled ? enteredAt_ - clickedAt_ : -1) +
           ", \"error\": " + jsonNumber(error) + ", \"closest\": " + jsonNumber(closest_) +
           ", \"grasp\": " + jsonQuoted(handGraspState(sandbox)) + ", \"time\": " + jsonNumber(t) +
           ", \"frames\": " + jsonNumber(frame) + "}";
  return false;
}

}  // namespace cablelab::ui
