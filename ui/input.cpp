#include "ui/input.h"

#include <imgui.h>

namespace cablelab::ui {

const char* const kShortcuts[][2] = {{"space", "play / pause"},
                                     {"s", "single step (pauses)"},
                                     {"r", "reset the scene"},
                                     {"h, F1", "this help"},
                                     {"+ / -", "zoom in / out"},
                                     {"wheel", "zoom about the cursor"},
                                     {"left drag", "drag a dynamic body"},
                                     {"left click", "set the controller target (empty space)"},
                                     {"right drag", "pan"},
                                     {nullptr, nullptr}};

namespace {

bool overPanel(const Sandbox& sandbox, const Vec2& mouse) {
  for (const PanelRect& p : sandbox.panels)
    if (p.contains(mouse)) return true;
  return ImGui::IsAnyItemActive();  // a slider or text field owns the mouse
}

void mouseDown(Sandbox& sandbox, const SDL_MouseButtonEvent& e) {
  const Vec2 mouse(e.x, e.y);
  World* world = sandbox.world();
  if (!world || overPanel(sandbox, mouse)) return;
  const Vec2 point = sandbox.camera.toWorld(mouse);
  if (e.button == SDL_BUTTON_LEFT) {
    const int body = sandbox.bodyAt(point);
    if (body >= 0) {
      const BodyState& s = world->body(body);
      sandbox.gesture = {Gesture::Kind::DragBody, mouse, rotate(point - s.position, -s.angle)};
      sandbox.selectedBody = body;
      world->beginDrag(body, point);
    } else {
      sandbox.target = point;
    }
  } else if (e.button == SDL_BUTTON_RIGHT) {
    sandbox.gesture = {Gesture::Kind::Pan, mouse, Vec2::Zero()};
  }
}

void mouseUp(Sandbox& sandbox, const SDL_MouseButtonEvent& e) {
  World* world = sandbox.world();
  if (sandbox.gesture.kind == Gesture::Kind::DragBody && e.button == SDL_BUTTON_LEFT) {
    if (world) world->endDrag();
    sandbox.gesture = {};
  } else if (sandbox.gesture.kind == Gesture::Kind::Pan && e.button == SDL_BUTTON_RIGHT) {
    sandbox.gesture = {};
  }
}

void mouseMotion(Sandbox& sandbox, const SDL_MouseMotionEvent& e) {
  const Vec2 mouse(e.x, e.y);
  World* world = sandbox.world();
  if (sandbox.gesture.kind == Gesture::Kind::DragBody && world) {
    world->dragTo(sandbox.camera.toWorld(mouse));
  } else if (sandbox.gesture.kind == Gesture::Kind::Pan) {
    sandbox.camera.panPixels(mouse - sandbox.gesture.lastMouse);
  }
  sandbox.gesture.lastMouse = mouse;
}

void key(Sandbox& sandbox, const SDL_KeyboardEvent& e) {
  if (ImGui::GetIO().WantTextInput) return;
  const Vec2 centre(0.5 * sandbox.camera.width, 0.5 * sandbox.camera.height);
  switch (e.keysym.sym) {
    case SDLK_SPACE:
      sandbox.paused = !sandbox.paused;
      break;
    case SDLK_s:
      sandbox.paused = true;
      ++sandbox.pendingSteps;
      break;
    case SDLK_r:
      sandbox.reset();
      break;
    case SDLK_h:
    case SDLK_F1:
      sandbox.showHelp = !sandbox.showHelp;
      break;
    case SDLK_PLUS:
    case SDLK_EQUALS:
    case SDLK_KP_PLUS:
      sandbox.camera.zoomAt(centre, 1.25);
      break;
    case SDLK_MINUS:
    case SDLK_KP_MINUS:
      sandbox.camera.zoomAt(centre, 1 / 1.25);
      break;
    case SDLK_ESCAPE:
      sandbox.showHelp = false;
      break;
    default:
      break;
  }
}

}  // namespace

void handleEvent(Sandbox& sandbox, const SDL_Event& event) {
  switch (event.type) {
    case SDL_MOUSEBUTTONDOWN:
      mouseDown(sandbox, event.button);
      break;
    case SDL_MOUSEBUTTONUP:
      mouseUp(sandbox, event.button);
      break;
    case SDL_MOUSEMOTION:
      mouseMotion(sandbox, event.motion);
      break;
    case SDL_MOUSEWHEEL: {
      int x = 0, y = 0;
      SDL_GetMouseState(&x, &y);
      const Vec2 mouse(x, y);
      if (!overPanel(sandbox, mouse) && event.wheel.y != 0)
        sandbox.camera.zoomAt(mouse, event.wheel.y > 0 ? 1.15 : 1 / 1.15);
      break;
    }
    case SDL_KEYDOWN:
      if (!event.key.repeat || event.key.keysym.sym == SDLK_s) key(sandbox, event.key);
      break;
    case SDL_WINDOWEVENT:
      if (event.window.event == SDL_WINDOWEVENT_SIZE_CHANGED)
        sandbox.resize(event.window.data1, event.window.data2);
      break;
    default:
      break;
  }
}

}  // namespace cablelab::ui
