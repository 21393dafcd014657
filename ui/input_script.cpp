#include "ui/input_script.h"

#include <cmath>
#include <cstdio>

#include "ui/panels.h"
#include "ui/synthetic_events.h"

namespace cablelab::ui {
namespace {

// Frame schedule of the script.
constexpr int kPress = 3, kMoveFrames = 30, kRelease = 90, kClick = 95, kCheck = 98, kKeys = 99,
              kEnd = 102;

bool inFreeArea(const Sandbox& sandbox, const Vec2& s) {
  const PanelRect f = sandbox.freeArea();
  return s.x() > f.x + 20 && s.x() < f.x + f.width - 20 && s.y() > f.y + 20 &&
         s.y() < f.y + f.height - 20;
}

}  // namespace

void InputScript::pushKey(SDL_Keycode key) {
  pushKeyPress(windowId_, key);
}

void InputScript::push(Uint32 type, const Vec2& screen, Uint8 button) {
  pushMouseEvent(windowId_, type, screen, button);
}

bool InputScript::beforeFrame(Sandbox& sandbox, int frame) {
  World* world = sandbox.world();
  if (!world) {
    failure_ = "no scene loaded";
    return false;
  }
  if (frame == kPress) {
    sandbox.paused = false;
    // Prefer a free body (no joint holds it), so that it can follow the mouse anywhere.
    const SceneDef& scene = world->scene();
    auto jointed = [&](int i) {
      for (const JointDef& j : scene.joints)
        if (j.bodyA == scene.bodies[i].name || j.bodyB == scene.bodies[i].name) return true;
      return false;
    };
    for (int pass = 0; pass < 2 && body_ < 0; ++pass)
      for (int i = 0; i < world->bodyCount() && body_ < 0; ++i) {
        const Vec2 s = sandbox.camera.toScreen(world->body(i).position);
        if ((pass == 1 || !jointed(i)) && inFreeArea(sandbox, s) &&
            sandbox.bodyAt(world->body(i).position) == i)
          body_ = i;
      }
    if (body_ < 0) {
      failure_ = "no dynamic body whose origin is inside its shape in the free area";
      return false;
    }
    bodyName_ = world->scene().bodies[body_].name;
    start_ = world->body(body_).position;
    from_ = sandbox.camera.toScreen(start_);
    const PanelRect f = sandbox.freeArea();
    const Vec2 centre(f.x + 0.5 * f.width, f.y + 0.5 * f.height);
    const Vec2 toward = centre - from_;
    to_ = from_ + Vec2(toward.x() >= 0 ? 90 : -90, toward.y() >= 0 ? 60 : -60);
    goal_ = sandbox.camera.toWorld(to_);
    push(SDL_MOUSEMOTION, from_);
    push(SDL_MOUSEBUTTONDOWN, from_);
  } else if (frame > kPress && frame <= kPress + kMoveFrames) {
    dragSeen_ = dragSeen_ || sandbox.drag.body == body_;
    push(SDL_MOUSEMOTION, from_ + (to_ - from_) * (frame - kPress) / double(kMoveFrames));
  } else if (frame == kRelease) {
    dragSeen_ = dragSeen_ && sandbox.drag.body == body_;
    end_ = world->body(body_).position;
    push(SDL_MOUSEBUTTONUP, to_);
  } else if (frame == kClick) {
    // An empty point of the free area: scan a coarse grid for one with no body under it.
    // Ctrl + click sets a target in any scene (a plain click only where a controller uses it).
    bool found = false;
    const PanelRect f = sandbox.freeArea();
    for (int gy = 0; gy < 8 && !found; ++gy)
      for (int gx = 0; gx < 8 && !found; ++gx) {
        const Vec2 s(f.x + 40 + gx * 0.125 * (f.width - 80),
                     f.y + 40 + gy * 0.125 * (f.height - 80));
        const Vec2 w = sandbox.camera.toWorld(s);
        if (sandbox.bodyAt(w, true) < 0 &&
            sandbox.cableAt(w, 10 * sandbox.camera.metresPerPixel) < 0)
          click_ = s, found = true;
      }
    sandbox.target.reset();
    SDL_SetModState(KMOD_LCTRL);
    push(SDL_MOUSEMOTION, click_);
    push(SDL_MOUSEBUTTONDOWN, click_);
    push(SDL_MOUSEBUTTONUP, click_);
  } else if (frame == kCheck) {
    SDL_SetModState(KMOD_NONE);
    targetSet_ = sandbox.target.has_value();
    if (targetSet_) targetError_ = (*sandbox.target - sandbox.camera.toWorld(click_)).norm();
  } else if (frame == kKeys) {
    pausedBefore_ = sandbox.paused;
    pushKey(SDLK_h);
    pushKey(SDLK_SPACE);
  } else if (frame >= kEnd) {
    keysOk_ = sandbox.showHelp && sandbox.paused != pausedBefore_;
    const double before = (start_ - goal_).norm(), after = (end_ - goal_).norm();
    const bool followed = after < 0.5 * before;
    const bool targetOk = targetSet_ && targetError_ <= 2 * sandbox.camera.metresPerPixel;
    passed_ = dragSeen_ && followed && targetOk && keysOk_;
    if (!dragSeen_)
      failure_ = "World::draggedBody() did not report the dragged body";
    else if (!followed)
      failure_ = "the body did not follow the mouse";
    else if (!targetOk)
      failure_ = "the click did not set the target";
    return false;
  }
  return true;
}

std::string InputScript::report() const {
  char buffer[768];
  std::snprintf(buffer, sizeof buffer,
                "{\"test_input\": %s, \"body\": \"%s\", \"start\": [%.17g, %.17g], "
                "\"goal\": [%.17g, %.17g], \"end\": [%.17g, %.17g], \"drag_seen\": %s, "
                "\"target_set\": %s, \"target_error\": %.17g, \"keys\": %s, \"failure\": \"%s\"}",
                passed_ ? "true" : "false", bodyName_.c_str(), start_.x(), start_.y(), goal_.x(),
                goal_.y(), end_.x(), end_.y(), dragSeen_ ? "true" : "false",
                targetSet_ ? "true" : "false", targetError_, keysOk_ ? "true" : "false",
                failure_.c_str());
  return buffer;
}

}  // namespace cablelab::ui
