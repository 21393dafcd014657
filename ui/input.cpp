#include "ui/input.h"

#include <imgui.h>

#include <iterator>

#include "ui/authoring.h"
#include "ui/controller_panel.h"
#include "ui/presentation.h"
#include "ui/timeline_panel.h"

namespace cablelab::ui {

const char* const kShortcuts[][2] = {{"space", "play / pause"},
                                     {"s", "single step (pauses)"},
                                     {"b", "step back (pauses; the last 30 s are kept)"},
                                     {"r", "reset the scene"},
                                     {"[ / ]", "slower / faster (0.1x .. 4x)"},
                                     {"f", "camera follows the selected body"},
                                     {"p", "presentation mode: panels hidden, scene fitted"},
                                     {"v", "fit the scene to the view"},
                                     {"Build menu", "add boxes, pulleys, cables by clicks"},
                                     {"Esc", "stop building: clicks select and drag"},
                                     {"F12", "screenshot (PNG in the working directory)"},
                                     {"F9", "start / stop recording a clip (MP4 or GIF)"},
                                     {"h, F1", "this help"},
                                     {"+ / -", "zoom in / out"},
                                     {"wheel", "zoom about the cursor"},
                                     {"left click", "select a body or a cable"},
                                     {"left drag", "drag a body (force-limited; paused: pose)"},
                                     {"Shift + drag", "paused: pose, letting the cable out"},
                                     {"click empty space", "set the target (hand scene)"},
                                     {"Ctrl + click", "set a target anywhere"},
                                     {"right drag", "pan"},
                                     {"Ctrl+Z / Ctrl+Y", "undo / redo a scene edit"},
                                     {"Delete", "delete the selected body"},
                                     {"drop a .json file", "open it as a scene"},
                                     {nullptr, nullptr}};

double stepSpeed(double speed, int direction) {
  if (direction > 0) {
    for (double s : kSpeeds)
      if (s > speed + 1e-9) return s;
    return kSpeeds[std::size(kSpeeds) - 1];
  }
  for (int k = static_cast<int>(std::size(kSpeeds)) - 1; k >= 0; --k)
    if (kSpeeds[k] < speed - 1e-9) return kSpeeds[k];
  return kSpeeds[0];
}

namespace {

bool overPanel(const Sandbox& sandbox, const Vec2& mouse) {
  for (const PanelRect& p : sandbox.panels)
    if (p.contains(mouse)) return true;
  // An open menu (or dialog) takes the click, over the view too: a pick in the Build menu put a
  // box under it. A click beside it shuts it, as in any program, and adds nothing.
  return ImGui::IsAnyItemActive() ||  // a slider or text field owns the mouse
         ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId);
}

void leftDown(Sandbox& sandbox, World& world, const Vec2& mouse, const Vec2& point) {
  const SDL_Keymod mods = SDL_GetModState();
  if (authoringClick(sandbox, point, false, mods & KMOD_SHIFT, mods & KMOD_ALT)) return;
  if (grabsTargetAngleHandle(sandbox, point)) {  // the hand's target angle (controller_panel.h)
    sandbox.gesture = {Gesture::Kind::TurnTarget, mouse, Vec2::Zero()};
    return;
  }
  const int body = sandbox.bodyAt(point, true);
  const bool ctrl = (SDL_GetModState() & KMOD_CTRL) != 0;
  if (ctrl) {
    sandbox.target = point;
    return;
  }
  if (body >= 0) {
    sandbox.selectedBody = body;
    if (world.scene().bodies[body].type == BodyType::Dynamic) {
      const BodyState& s = world.body(body);
      sandbox.gesture = {Gesture::Kind::DragBody, mouse, rotate(point - s.position, -s.angle)};
      sandbox.beginDrag(body, point);
    }
    return;
  }
  const int cable = sandbox.cableAt(point, 6 * sandbox.camera.metresPerPixel);
  if (cable >= 0) {
    sandbox.selectedCable = cable;
    sandbox.watchedCable = cable;
    sandbox.showInspector = true;
    const Cable& c = world.cable(cable);
    sandbox.cableEdit = {c.restLength(), c.stiffness(), c.preload(), c.damping()};
    return;
  }
  sandbox.watchedCable = -1;
  if (sandbox.hasController())
    sandbox.target = point;
  else
    sandbox.selectedBody = -1;
}

void mouseDown(Sandbox& sandbox, const SDL_MouseButtonEvent& e) {
  const Vec2 mouse(e.x, e.y);
  World* world = sandbox.world();
  if (!world || overPanel(sandbox, mouse)) return;
  const Vec2 point = sandbox.camera.toWorld(mouse);
  if (e.button == SDL_BUTTON_LEFT)
    leftDown(sandbox, *world, mouse, point);
  else if (e.button == SDL_BUTTON_RIGHT && !authoringClick(sandbox, point, true))
    sandbox.gesture = {Gesture::Kind::Pan, mouse, Vec2::Zero()};
}

void mouseUp(Sandbox& sandbox, const SDL_MouseButtonEvent& e) {
  if (sandbox.gesture.kind == Gesture::Kind::DragBody && e.button == SDL_BUTTON_LEFT) {
    sandbox.endDrag();
    sandbox.gesture = {};
  } else if ((sandbox.gesture.kind == Gesture::Kind::Pan && e.button == SDL_BUTTON_RIGHT) ||
             (sandbox.gesture.kind == Gesture::Kind::TurnTarget && e.button == SDL_BUTTON_LEFT)) {
    sandbox.gesture = {};
  }
}

void mouseMotion(Sandbox& sandbox, const SDL_MouseMotionEvent& e) {
  const Vec2 mouse(e.x, e.y);
  if (sandbox.gesture.kind == Gesture::Kind::DragBody && sandbox.world()) {
    sandbox.dragTo(sandbox.camera.toWorld(mouse), (SDL_GetModState() & KMOD_SHIFT) != 0);
  } else if (sandbox.gesture.kind == Gesture::Kind::TurnTarget) {
    dragTargetAngle(sandbox, sandbox.camera.toWorld(mouse));
  } else if (sandbox.gesture.kind == Gesture::Kind::Pan) {
    sandbox.camera.panPixels(mouse - sandbox.gesture.lastMouse);
    sandbox.follow = false;
    sandbox.viewFitted = false;  // the user's view now: layout changes keep it
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
    case SDLK_z:
      if (SDL_GetModState() & KMOD_CTRL)
        (SDL_GetModState() & KMOD_SHIFT) ? redoEdit(sandbox) : undoEdit(sandbox);
      break;
    case SDLK_y:
      if (SDL_GetModState() & KMOD_CTRL) redoEdit(sandbox);
      break;
    case SDLK_DELETE:
      if (sandbox.selectedBody >= 0 && sandbox.world()) {
        const BodyState& b = sandbox.world()->body(sandbox.selectedBody);
        const Authoring::Tool tool = sandbox.authoring->tool;
        sandbox.authoring->tool = Authoring::Tool::Delete;
        authoringClick(sandbox, b.position, false);
        sandbox.authoring->tool = tool;
      }
      break;
    case SDLK_s:
      sandbox.paused = true;
      ++sandbox.pendingSteps;
      break;
    case SDLK_b:
      stepBack(sandbox);
      break;
    case SDLK_r:
      sandbox.reset();
      break;
    case SDLK_h:
    case SDLK_F1:
      sandbox.showHelp = !sandbox.showHelp;
      break;
    case SDLK_f:
      sandbox.follow = !sandbox.follow && sandbox.selectedBody >= 0;
      break;
    case SDLK_LEFTBRACKET:
      sandbox.speed = stepSpeed(sandbox.speed, -1);
      break;
    case SDLK_RIGHTBRACKET:
      sandbox.speed = stepSpeed(sandbox.speed, +1);
      break;
    case SDLK_F12:
      sandbox.screenshotRequested = true;
      break;
    case SDLK_F9:
      sandbox.recordToggleRequested = true;
      break;
    case SDLK_PLUS:
    case SDLK_EQUALS:
    case SDLK_KP_PLUS:
      sandbox.camera.zoomAt(centre, 1.25);
      sandbox.viewFitted = false;
      break;
    case SDLK_MINUS:
    case SDLK_KP_MINUS:
      sandbox.camera.zoomAt(centre, 1 / 1.25);
      sandbox.viewFitted = false;
      break;
    case SDLK_p:
      togglePresentation(sandbox);
      break;
    case SDLK_v:
      sandbox.fitView();
      break;
    case SDLK_ESCAPE:  // closes the help, else stops building
      if (!sandbox.showHelp) chooseTool(*sandbox.authoring, Authoring::Tool::None);
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
      if (!overPanel(sandbox, mouse) && event.wheel.y != 0) {
        sandbox.camera.zoomAt(mouse, event.wheel.y > 0 ? 1.15 : 1 / 1.15);
        sandbox.viewFitted = false;
      }
      break;
    }
    case SDL_KEYDOWN:
      if (!event.key.repeat || event.key.keysym.sym == SDLK_s || event.key.keysym.sym == SDLK_b)
        key(sandbox, event.key);
      break;
    case SDL_DROPFILE:
      if (event.drop.file) {
        sandbox.open(event.drop.file);
        SDL_free(event.drop.file);
      }
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
