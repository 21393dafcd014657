#include "ui/first_mechanism_script.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "engine/model/scene_json.h"
#include "ui/lecture_scripts.h"
#include "ui/report_json.h"
#include "ui/synthetic_events.h"

namespace cablelab::ui {
namespace {

using Tool = Authoring::Tool;

constexpr int kSizes[2][2] = {{1280, 720}, {1920, 1080}};
constexpr int kRunFrames = 20;   ///< the mechanism runs this long before the drag
constexpr int kDragFrames = 10;  ///< the drag's length in frames

Vec2 centre(const PanelRect& r) {
  return Vec2(r.x + 0.5 * r.width, r.y + 0.5 * r.height);
}

/// `r` as [x0, y0, x1, y1] (px), null when empty.
std::string rectJson(const PanelRect& r) {
  if (r.width <= 0 || r.height <= 0) return "null";
  return "[" + jsonNumber(r.x) + ", " + jsonNumber(r.y) + ", " + jsonNumber(r.x + r.width) + ", " +
         jsonNumber(r.y + r.height) + "]";
}

int dynamicBodies(const SceneDef& scene) {
  return static_cast<int>(
      std::count_if(scene.bodies.begin(), scene.bodies.end(),
                    [](const BodyDef& b) { return b.type == BodyType::Dynamic; }));
}

}  // namespace

FirstMechanismScript::FirstMechanismScript(Uint32 windowId, std::string out)
    : windowId_(windowId), out_(std::move(out)) {
  add("projector mode", 1, [](Sandbox& s, int) {
    s.projector = true;  // the View menu's projector mode, at twice the text size
    s.uiScale = 2;
    return true;
  });
  key(SDLK_p);
  wait(2);
  for (const auto& size : kSizes) {
    size_ = std::to_string(size[1]) + "-";
    atSize(size[0], size[1]);
    openBuildMenu();
    shot("menu");
    click(
        "Build > New scene", [](const Sandbox& s) { return s.authoring->menu.newScene; },
        [this, size = size_](Sandbox& s) {
          newScenes_.push_back(
              "{\"size\": " + jsonQuoted(size) + ", \"name\": " + jsonQuoted(s.displayName()) +
              ", \"bodies\": " + jsonNumber(s.scene.bodies.size()) +
              ", \"dynamic_bodies\": " + jsonNumber(dynamicBodies(s.scene)) + ", \"cables\": " +
              jsonNumber(s.scene.cables.size()) + ", \"paused\": " + (s.paused ? "true" : "false") +
              ", \"menu_open\": " + (s.authoring->menu.open ? "true" : "false") + "}");
        });
    wait(3);
    shot("new");
    buildMechanism();
    add("stop building", 1, [this](Sandbox&, int) {
      building_ = false;
      return true;
    });
    key(SDLK_ESCAPE);  // stop building: the view fits the mechanism
    wait(3);
    shot("built");
    runAndDrag(size[0]);
  }
  key(SDLK_p);  // the side panels again
  wait(7);
  size_.clear();
  shot("panels");
}

void FirstMechanismScript::add(std::string what, int frames,
                               std::function<bool(Sandbox&, int)> act) {
  steps_.push_back({std::move(what), frames, std::move(act)});
}

void FirstMechanismScript::atSize(int width, int height) {
  add("window size", 1, [this, width, height](Sandbox&, int) {
    // The window fills the projector's screen (Xvfb's is 1920x1080): its top-left corner in the
    // screen's, so that the pointer reaches every point of it.
    SDL_Window* window = SDL_GetWindowFromID(windowId_);
    SDL_SetWindowPosition(window, 0, 0);
    SDL_SetWindowSize(window, width, height);
    return true;
  });
  wait(8);
}

void FirstMechanismScript::click(const std::string& what, Where where,
                                 std::function<void(Sandbox&)> then) {
  add(what, 5, [this, what, where, then](Sandbox& s, int f) {
    if (f == 0) {
      const PanelRect r = where(s);
      if (r.width <= 0 || r.height <= 0) return false;
      at_ = centre(r);
      movePointer(windowId_, at_);
    } else if (f == 1) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, at_);
    } else if (f == 2) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, at_);
    } else if (f == 4 && then) {
      then(s);
    }
    return true;
  });
}

void FirstMechanismScript::openBuildMenu() {
  // A click on "Build" in the top bar, unless the menu is open already (a click would shut it).
  add("Build", 5, [this](Sandbox& s, int f) {
    const BuildMenuLayout& menu = s.authoring->menu;
    if (f == 0) {
      if (menu.open) {
        at_ = Vec2(-1, -1);  // open: nothing to click
        return true;
      }
      if (menu.title.width <= 0) return false;
      at_ = centre(menu.title);
      movePointer(windowId_, at_);
    } else if (at_.x() >= 0 && f == 1) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, at_);
    } else if (at_.x() >= 0 && f == 2) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, at_);
    } else if (f == 4) {
      return menu.open;  // the menu did not open
    }
    return true;
  });
}

void FirstMechanismScript::pickTool(Tool tool) {
  openBuildMenu();
  auto bodies = std::make_shared<size_t>(0);
  add("count bodies", 1, [bodies](Sandbox& s, int) {
    *bodies = s.scene.bodies.size();
    return true;
  });
  click(
      std::string("Build > ") + toolName(tool),
      [tool](const Sandbox& s) {
        const auto& items = s.authoring->menu.tools;
        const auto k = static_cast<size_t>(tool);
        return k < items.size() ? items[k] : PanelRect{};
      },
      [this, tool, bodies, size = size_](Sandbox& s) {
        const Authoring& a = *s.authoring;
        picks_.push_back("{\"size\": " + jsonQuoted(size) +
                         ", \"item\": " + jsonQuoted(toolName(tool)) +
                         ", \"chosen\": " + jsonQuoted(toolName(a.tool)) +
                         ", \"menu_open\": " + (a.menu.open ? "true" : "false") +
                         ", \"clicked\": [" + jsonNumber(at_.x()) + ", " + jsonNumber(at_.y()) +
                         "]" + ", \"bodies_before\": " + jsonNumber(*bodies) +
                         ", \"bodies_after\": " + jsonNumber(s.scene.bodies.size()) + "}");
      });
}

void FirstMechanismScript::viewClick(const Vec2& world) {
  add("click in the view", 4, [this, world](Sandbox& s, int f) {
    if (f == 0) {
      at_ = s.camera.toScreen(world);
      if (!s.freeArea().contains(at_)) ++clicksOffView_;
      movePointer(windowId_, at_);
    } else if (f == 1) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, at_);
    } else if (f == 2) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, at_);
    }
    return true;
  });
}

void FirstMechanismScript::typeInField(const std::string& field, Where where,
                                       const std::string& text) {
  openBuildMenu();
  // The pointer onto "next body" opens its submenu (a click if resting there does not).
  add("Build > next body", 6, [this](Sandbox& s, int f) {
    const BuildMenuLayout& menu = s.authoring->menu;
    if (f == 0) {
      if (menu.nextBody.width <= 0) return false;
      at_ = centre(menu.nextBody);
      movePointer(windowId_, at_);
    } else if (f == 2 && !menu.nextBodyOpen) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, at_);
    } else if (f == 3 && !menu.nextBodyOpen) {
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, at_);
    } else if (f == 5) {
      return menu.nextBodyOpen;
    }
    return true;
  });
  add("Build > next body > " + field, 9,
      [this, field, where, text, size = size_](Sandbox& s, int f) {
        switch (f) {
          case 0: {  // Ctrl down, the pointer onto the field
            const PanelRect r = where(s);
            if (r.width <= 0) return false;
            at_ = centre(r);
            before_ = field == "kg" ? s.authoring->mass : s.authoring->size;
            s.error.clear();  // the last field's complaint dismissed (its Dismiss button)
            SDL_SetModState(KMOD_LCTRL);
            pushKeyEvent(windowId_, SDL_KEYDOWN, SDLK_LCTRL);
            movePointer(windowId_, at_);
            break;
          }
          case 1:
            pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, at_);
            break;
          case 2:
            pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, at_);
            break;
          case 3:
            SDL_SetModState(KMOD_NONE);
            pushKeyEvent(windowId_, SDL_KEYUP, SDLK_LCTRL);
            break;
          case 4:
            pushText(windowId_, text.c_str());
            break;
          case 5:
            pushKeyEvent(windowId_, SDL_KEYDOWN, SDLK_RETURN);
            break;
          case 6:
            pushKeyEvent(windowId_, SDL_KEYUP, SDLK_RETURN);
            break;
          case 8: {
            const Authoring& a = *s.authoring;
            fields_.push_back(
                "{\"size\": " + jsonQuoted(size) + ", \"field\": " + jsonQuoted(field) +
                ", \"typed\": " + jsonQuoted(text) +
                ", \"value\": " + jsonNumber(field == "kg" ? a.mass : a.size) +
                ", \"before\": " + jsonNumber(before_) + ", \"error\": " + jsonQuoted(s.error) +
                ", \"menu_open\": " + (a.menu.open ? "true" : "false") +
                ", \"error_box\": " + rectJson(s.error.empty() ? PanelRect{} : s.errorBox) +
                ", \"menus\": [" + rectJson(a.menu.popup) + ", " +
                rectJson(a.menu.nextBodyOpen ? a.menu.nextBodyPopup : PanelRect{}) + "]}");
            break;
          }
          default:
            break;
        }
        return true;
      });
}

void FirstMechanismScript::key(SDL_Keycode k) {
  add("key", 1, [this, k](Sandbox&, int) {
    pushKeyPress(windowId_, k);
    return true;
  });
}

void FirstMechanismScript::shot(const std::string& name) {
  add("screenshot", 1, [this, name = size_ + name](Sandbox& s, int) {
    pending_ = name;
    s.pngRequest =
        PanelRect{0, 0, static_cast<float>(s.camera.width), static_cast<float>(s.camera.height)};
    s.pngRequestPath = out_ + "-" + name + ".png";
    return true;
  });
  wait(1);  // its view is recorded next frame
}

void FirstMechanismScript::wait(int frames) {
  add("wait", frames, [](Sandbox&, int) { return true; });
}

void FirstMechanismScript::buildMechanism() {
  add("start building", 1, [this](Sandbox&, int) { return building_ = true; });
  // Every body and pulley of the size and mass in the menu's fields when it is clicked (they
  // keep their values across New scene: the first box's are typed too).
  openBuildMenu();
  shot("menu-tools");
  // What the field cannot take first: a negative mass, a zero size, a number past a float's.
  const auto massField = [](const Sandbox& s) { return s.authoring->menu.mass; };
  const auto sizeField = [](const Sandbox& s) { return s.authoring->menu.size; };
  typeInField("kg", massField, "-1");
  add("screenshot", 1, [this, name = size_ + "refused"](Sandbox& s, int) {
    s.pngRequest =
        PanelRect{0, 0, static_cast<float>(s.camera.width), static_cast<float>(s.camera.height)};
    s.pngRequestPath = out_ + "-" + name + ".png";
    return true;
  });
  typeInField("size (m)", sizeField, "0");
  typeInField("size (m)", sizeField, "1e999");
  typeInField(
      "size (m)", [](const Sandbox& s) { return s.authoring->menu.size; }, "0.4");
  typeInField(
      "kg", [](const Sandbox& s) { return s.authoring->menu.mass; }, "1");
  pickTool(Tool::Box);
  viewClick(Vec2(-0.8, 1));  // box1, the light one (1 kg)
  typeInField(
      "kg", [](const Sandbox& s) { return s.authoring->menu.mass; }, "2");
  shot("menu-kg");
  pickTool(Tool::Box);
  viewClick(Vec2(1.4, 1));  // box2, 2 kg
  typeInField(
      "size (m)", [](const Sandbox& s) { return s.authoring->menu.size; }, "0.8");
  pickTool(Tool::CirclePulley);
  viewClick(Vec2(-0.4, 2.5));
  pickTool(Tool::PolygonPulley);
  viewClick(Vec2(0.6, 2.5));
  pickTool(Tool::PointPulley);
  viewClick(Vec2(1.4, 1.9));
  pickTool(Tool::Cable);  // from box1's top, over the pulleys in order, to box2's top
  for (const Vec2& p :
       {Vec2(-0.8, 1.1), Vec2(-0.4, 2.5), Vec2(0.6, 2.5), Vec2(1.4, 1.9), Vec2(1.4, 1.1)})
    viewClick(p);
  wait(2);
  add("built", 1, [this, size = size_](Sandbox& s, int) {
    std::vector<std::string> kinds;
    for (const CableDef& c : s.scene.cables)
      for (const PulleyDef& p : c.pulleys) kinds.push_back(jsonQuoted(pulleyTypeName(p.kind)));
    int wraps = 0;
    for (int i = 0; i < s.world()->cableCount(); ++i) wraps += s.world()->cable(i).wraps();
    builds_.push_back(
        "{\"size\": " + jsonQuoted(size) + ", \"bodies\": " + jsonNumber(s.scene.bodies.size()) +
        ", \"dynamic_bodies\": " + jsonNumber(dynamicBodies(s.scene)) +
        ", \"cables\": " + jsonNumber(s.scene.cables.size()) + ", \"pulleys\": " + jsonList(kinds) +
        ", \"wraps\": " + jsonNumber(wraps) + ", \"error\": " + jsonQuoted(s.error) + "}");
    return true;
  });
}

void FirstMechanismScript::runAndDrag(int width) {
  key(SDLK_SPACE);
  wait(kRunFrames);
  shot("run");
  // The light box dragged sideways as it rises, and let go.
  add("drag", kDragFrames + 1, [this, width](Sandbox& s, int f) {
    if (f == 0) {
      body_ = s.world()->findBody("box1");
      if (body_ < 0) return false;
      from_ = s.camera.toScreen(s.world()->body(body_).position);
      to_ = from_ + Vec2(-0.1 * width, 0);
      movePointer(windowId_, from_);
      pushMouseEvent(windowId_, SDL_MOUSEBUTTONDOWN, from_);
    } else {
      movePointer(windowId_, from_ + (to_ - from_) * (static_cast<double>(f) / kDragFrames));
    }
    return true;
  });
  wait(1);
  shot("drag");
  add("let go", 1, [this](Sandbox&, int) {
    pushMouseEvent(windowId_, SDL_MOUSEBUTTONUP, to_);
    return true;
  });
  wait(1);
  key(SDLK_SPACE);
  wait(4);
  shot("paused");
}

bool FirstMechanismScript::beforeFrame(Sandbox& sandbox) {
  if (!pending_.empty()) {
    views_.push_back(lectureViewJson(sandbox, pending_, out_ + "-" + pending_ + ".png"));
    pending_.clear();
  }
  if (!sandbox.banner.empty() &&
      (banners_.empty() || banners_.back() != jsonQuoted(sandbox.banner)))
    banners_.push_back(jsonQuoted(sandbox.banner));
  if (building_) {  // the view holds still under the student's clicks
    const Camera& c = sandbox.camera;
    if (c.center != buildCamera_.center || c.metresPerPixel != buildCamera_.metresPerPixel)
      ++buildViewMoves_;
  }
  buildCamera_ = sandbox.camera;
  if (step_ >= steps_.size()) {
    report_ = finalReport(sandbox);
    return false;
  }
  Step& step = steps_[step_];
  if (!step.act(sandbox, stepFrame_)) {
    report_ = "{\"scenario\": \"first-mechanism\", \"failure\": " +
              jsonQuoted(step.what + " (step " + std::to_string(step_) + ", frame " +
                         std::to_string(stepFrame_) + ")") +
              ", \"views\": " + jsonList(views_) + "}";
    return false;
  }
  if (++stepFrame_ >= step.frames) {
    ++step_;
    stepFrame_ = 0;
  }
  return true;
}

std::string FirstMechanismScript::finalReport(const Sandbox& sandbox) const {
  return "{\"scenario\": \"first-mechanism\", \"bodies\": " +
         jsonNumber(sandbox.scene.bodies.size()) +
         ", \"cables\": " + jsonNumber(sandbox.scene.cables.size()) +
         ", \"error\": " + jsonQuoted(sandbox.error) + ", \"new_scenes\": " + jsonList(newScenes_) +
         ", \"picks\": " + jsonList(picks_) + ", \"fields\": " + jsonList(fields_) +
         ", \"builds\": " + jsonList(builds_) + ", \"banners\": " + jsonList(banners_) +
         ", \"build_view_moves\": " + jsonNumber(buildViewMoves_) +
         ", \"build_clicks_outside\": " + jsonNumber(clicksOffView_) +
         ", \"views\": " + jsonList(views_) + "}";
}

}  // namespace cablelab::ui
