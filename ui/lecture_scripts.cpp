#include "ui/lecture_scripts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "ui/authoring.h"
#include "ui/controller_panel.h"
#include "ui/first_mechanism_script.h"
#include "ui/plot_board.h"
#include "ui/plot_quantity.h"
#include "ui/report_json.h"
#include "ui/scene_bounds.h"
#include "ui/scene_catalog.h"
#include "ui/synthetic_events.h"
#include "ui/tension_scale.h"

namespace cablelab::ui {
namespace {

std::string box(const LabelBox& b) {
  if (b.empty()) return "null";
  return "[" + jsonNumber(b.x0) + ", " + jsonNumber(b.y0) + ", " + jsonNumber(b.x1) + ", " +
         jsonNumber(b.y1) + "]";
}

/// The Build menu as the last frame laid it out (ui/authoring.h, BuildMenuLayout), as JSON.
std::string buildMenuJson(const BuildMenuLayout& m) {
  const auto rect = [](const PanelRect& r) -> std::string {
    if (r.width <= 0 && r.height <= 0) return "null";
    return "[" + jsonNumber(r.x) + ", " + jsonNumber(r.y) + ", " + jsonNumber(r.x + r.width) +
           ", " + jsonNumber(r.y + r.height) + "]";
  };
  std::string items = "{\"New scene\": " + rect(m.newScene);
  for (size_t k = 0; k < m.tools.size(); ++k)
    items += ", " + jsonQuoted(toolName(static_cast<Authoring::Tool>(k))) + ": " + rect(m.tools[k]);
  items += ", \"next body\": " + rect(m.nextBody) + "}";
  return "{\"open\": " + std::string(m.open ? "true" : "false") + ", \"title\": " + rect(m.title) +
         ", \"popup\": " + rect(m.popup) + ", \"items\": " + items +
         ", \"next_body_open\": " + (m.nextBodyOpen ? "true" : "false") +
         ", \"next_body_popup\": " + rect(m.nextBodyPopup) +
         ", \"next_body_items\": {\"size (m)\": " + rect(m.size) + ", \"kg\": " + rect(m.mass) +
         "}" + ", \"row_overflow\": " + jsonNumber(m.rowOverflow) +
         ", \"hidden_height\": " + jsonNumber(m.hiddenHeight) + "}";
}

/// The side panels and their collapsed title bars, each [x0, y0, x1, y1] (px).
std::string panelsJson(const std::vector<PanelRect>& panels) {
  std::vector<std::string> out;
  for (const PanelRect& p : panels) {
    std::vector<std::string> corners = {jsonNumber(p.x), jsonNumber(p.y), jsonNumber(p.x + p.width),
                                        jsonNumber(p.y + p.height)};
    out.push_back(jsonList(corners));
  }
  return jsonList(out);
}

/// `r` alone, or nothing when it is empty (not drawn in the last frame).
std::vector<PanelRect> drawnAlone(const PanelRect& r) {
  if (r.width <= 0 || r.height <= 0) return {};
  return {r};
}

}  // namespace

std::string lectureViewJson(const Sandbox& s, const std::string& name, const std::string& shot) {
  const DrawnView& d = s.drawn;
  const FurnitureLayout& f = d.furniture;
  const PanelRect free = s.freeArea();
  std::string labels = "[";
  for (size_t k = 0; k < d.labels.size(); ++k) labels += (k ? ", " : "") + box(d.labels[k]);
  labels += "]";
  std::string markers = "[";
  for (size_t k = 0; k < d.markers.size(); ++k) markers += (k ? ", " : "") + box(d.markers[k]);
  markers += "]";
  std::string lines = "[";  // the overlay's lines as drawn, each [x0, y0, x1, y1] (px)
  for (size_t k = 0; k < d.overlayLines.size(); ++k) {
    const ScreenSegment& l = d.overlayLines[k];
    lines += std::string(k ? ", " : "") + "[" + jsonNumber(l.a.x()) + ", " + jsonNumber(l.a.y()) +
             ", " + jsonNumber(l.b.x()) + ", " + jsonNumber(l.b.y()) + "]";
  }
  lines += "]";
  std::vector<std::string> shownKeys, markerKeys;  // the key's rows; the overlay's markers' keys
  if (!f.key.empty())
    for (const MarkerKeyRow& r : f.keyRows) shownKeys.push_back(jsonQuoted(r.label));
  std::vector<std::string> notes;  // the overlay's notes (the clip's time stamp is the window's)
  const Overlay overlay = s.overlay();
  for (const Overlay::Key& k : overlay.keys) markerKeys.push_back(jsonQuoted(k.label));
  for (const std::string& n : overlay.notes) notes.push_back(jsonQuoted(n));
  // a looping demo's whole run on screen (ui/demo_loop.h), px
  const LabelBox stage = screenBox(s.demo.stage, s.camera);
  WorldBounds fixed;     // the fixed bodies (a ground), whole
  int bodiesInView = 0;  // dynamic bodies whose centre is in the free area
  if (const World* world = s.world())
    for (int i = 0; i < world->bodyCount(); ++i) {
      if (world->scene().bodies[i].type == BodyType::Static) {
        const WorldBounds b = bodyBounds(*world, i);
        fixed.include(b.lo);
        fixed.include(b.hi);
      }
      const Vec2 p = s.camera.toScreen(world->body(i).position);
      bodiesInView += world->scene().bodies[i].type == BodyType::Dynamic && p.x() >= free.x &&
                      p.x() <= free.x + free.width && p.y() >= free.y &&
                      p.y() <= free.y + free.height;
    }
  return "{\"name\": " + jsonQuoted(name) + ", \"scene_name\": " + jsonQuoted(s.sceneName) +
         ", \"window\": [" + jsonNumber(s.camera.width) + ", " + jsonNumber(s.camera.height) +
         "], \"free\": [" + jsonNumber(free.x) + ", " + jsonNumber(free.y) + ", " +
         jsonNumber(free.width) + ", " + jsonNumber(free.height) + "], \"scene\": " + box(d.scene) +
         ", \"stage\": " + box(stage) + ", \"labels\": " + labels + ", \"markers\": " + markers +
         ", \"overlay_lines\": " + lines + ", \"key_rows\": " + jsonList(shownKeys) +
         ", \"marker_keys\": " + jsonList(markerKeys) +
         ", \"hidden_labels\": " + jsonNumber(d.hiddenLabels) +
         ", \"labels_on_cables\": " + jsonNumber(d.labelsOnCables) +
         ", \"scale_bar\": " + box(f.scaleBar) + ", \"colour_bar\": " + box(f.colourBar) +
         ", \"key\": " + box(f.key) + ", \"notes\": " + box(f.notes) +
         ", \"notes_text\": " + jsonList(notes) + ", \"banner\": " + box(f.banner) +
         ", \"paused\": " + box(f.paused) + ", \"ui_scale\": " + jsonNumber(s.uiScale) +
         ", \"tension_scale\": " + jsonNumber(s.tensionScale) +
         ", \"presentation\": " + (s.presentation ? "true" : "false") +
         ", \"view_fitted\": " + (s.viewFitted ? "true" : "false") +
         ", \"close_up\": " + (s.closeUp ? "true" : "false") +
         ", \"bodies_in_view\": " + jsonNumber(bodiesInView) + ", \"overflow\": [" +
         jsonNumber(s.panelOverflow[0]) + ", " + jsonNumber(s.panelOverflow[1]) +
         "], \"status_overflow\": " + jsonNumber(s.statusOverflow) +
         ", \"status\": " + jsonQuoted(s.shownStatus) +
         ", \"truncated_buttons\": " + jsonNumber(s.truncatedButtons) +
         ", \"fixed\": " + box(screenBox(fixed, s.camera)) +
         ", \"strip_name\": " + jsonQuoted(s.shownStripName) +
         ", \"strip_overflow\": " + jsonNumber(s.stripOverflow) +
         ", \"title\": " + jsonQuoted(s.shownTitle) + ", \"panels\": " + panelsJson(s.panels) +
         ", \"speed_slider\": " + panelsJson(drawnAlone(s.speedSlider)) +
         ", \"speed_value\": " + panelsJson(drawnAlone(s.speedValue)) +
         ", \"record_button\": " + panelsJson(drawnAlone(s.recordButton)) +
         ", \"controller_section\": " + jsonQuoted(s.controllerSection) +
         ", \"building\": " + (s.building() ? "true" : "false") +
         ", \"build_menu\": " + buildMenuJson(s.authoring->menu) +
         ", \"screenshot\": " + jsonQuoted(shot) + "}";
}

namespace {

/// The built-in scene after `name` in the menu's order (the first after the last).
std::string nextScene(const std::string& name) {
  const auto all = builtinSceneList();
  for (size_t k = 0; k < all.size(); ++k)
    if (all[k].name == name) return all[(k + 1) % all.size()].name;
  return all.front().name;
}

/// The first dynamic body at a cable's end, or -1.
int bodyAtACableEnd(const World& world) {
  for (int i = 0; i < world.cableCount(); ++i) {
    const int b = world.findBody(world.cable(i).def().end.body);
    if (b >= 0 && world.scene().bodies[b].type == BodyType::Dynamic) return b;
  }
  return -1;
}

/// A point of a cable (none of a body) in the view, as the user clicks it (px); the view's
/// centre when there is none.
Vec2 cablePixel(const Sandbox& sandbox) {
  const PanelRect f = sandbox.freeArea();
  for (float y = f.y + 4; y < f.y + f.height; y += 3)
    for (float x = f.x + 4; x < f.x + f.width; x += 3) {
      const Vec2 p = sandbox.camera.toWorld(Vec2(x, y));
      if (sandbox.bodyAt(p, true) < 0 && sandbox.cableAt(p, 2 * sandbox.camera.metresPerPixel) >= 0)
        return Vec2(x, y);
    }
  return Vec2(f.x + 0.5 * f.width, f.y + 0.5 * f.height);
}

Vec2 middle(const LabelBox& b) {
  return Vec2(0.5 * (b.x0 + b.x1), 0.5 * (b.y0 + b.y1));
}

Vec2 middle(const PanelRect& r) {
  return Vec2(r.x + 0.5 * r.width, r.y + 0.5 * r.height);
}

/// The slider step of a built-in scene's "what to try" (ui/scene_guide.h), if it has one.
std::optional<std::pair<std::string, double>> sliderStep(const std::string& scene) {
  static const std::map<std::string, std::pair<std::string, double>> steps = {
      {"ballast", {"v0y", 3}},    {"pulley", {"m_left", 1}}, {"wheel", {"I", 0}},
      {"capstan", {"m_load", 6}}, {"winch", {"omega", -1}},  {"tackle", {"m_effort", 1}}};
  const auto it = steps.find(scene);
  if (it == steps.end()) return std::nullopt;
  return it->second;
}

/// The scene's "what to try" step that is not a drag: its slider step (the slider moved and let
/// go), or the hand's grasp sequence (the Controller section's "open (grasp)").
void tryStep(Sandbox& sandbox) {
  if (const auto step = sliderStep(sandbox.sceneName)) {
    auto values = sandbox.parameters;
    for (auto& [k, v] : values)
      if (k == step->first) v = step->second;
    sandbox.rebuild(values);
  } else if (sandbox.sceneName == "hand") {
    startHandGrasp(sandbox);
  }
}

}  // namespace

const std::vector<std::string>& LectureScript::names() {
  static const std::vector<std::string> n = {
      "present", "grasp-quiet",     "tension-run", "walkthrough", "select-rope",
      "tour",    "first-mechanism", "laptop",      "hand-export", "follow"};
  return n;
}

LectureScript::LectureScript(std::string name, Uint32 windowId, std::string out)
    : name_(std::move(name)), out_(std::move(out)), windowId_(windowId) {}

LectureScript::~LectureScript() = default;

void LectureScript::key(SDL_Keycode k) {
  pushKeyPress(windowId_, k);
}

void LectureScript::mouse(Uint32 type, const Vec2& screen) {
  pushMouseEvent(windowId_, type, screen);
}

// The View menu's projector mode, at twice the text size.
void LectureScript::projectorScale(Sandbox& sandbox) {
  sandbox.projector = true;
  sandbox.uiScale = 2;
}

void LectureScript::recordPendingView(Sandbox& sandbox) {
  if (pending_.empty()) return;
  items_.push_back(lectureViewJson(sandbox, pending_, out_ + "-" + pending_ + ".png"));
  pending_.clear();
}

void LectureScript::snapshot(Sandbox& sandbox, const char* name) {
  pending_ = name;
  sandbox.pngRequest = PanelRect{0, 0, static_cast<float>(sandbox.camera.width),
                                 static_cast<float>(sandbox.camera.height)};
  sandbox.pngRequestPath = out_ + "-" + pending_ + ".png";
}

bool LectureScript::beforeFrame(Sandbox& sandbox, int frame) {
  if (name_ == "present") return present(sandbox, frame);
  if (name_ == "grasp-quiet") return graspQuiet(sandbox, frame);
  if (name_ == "tension-run") return tensionRun(sandbox, frame);
  if (name_ == "walkthrough") return walkthrough(sandbox, frame);
  if (name_ == "select-rope") return selectRope(sandbox, frame);
  if (name_ == "tour") return tour(sandbox, frame);
  if (name_ == "first-mechanism") return firstMechanism(sandbox, frame);
  if (name_ == "laptop") return laptop(sandbox, frame);
  if (name_ == "hand-export") return handExport(sandbox, frame);
  if (name_ == "follow") return follow(sandbox, frame);
  report_ = "{\"scenario\": " + jsonQuoted(name_) + ", \"failure\": \"unknown scenario\"}";
  return false;
}

bool LectureScript::present(Sandbox& sandbox, int frame) {
  recordPendingView(sandbox);
  auto snapshot = [&](const char* name) { this->snapshot(sandbox, name); };
  SDL_Window* window = SDL_GetWindowFromID(windowId_);
  switch (frame) {
    case 3:
      key(SDLK_p);
      break;
    case 10:
      snapshot("presentation");
      break;
    case 12:  // the View menu's projector mode off, then on again
      sandbox.projector = false;
      sandbox.uiScale = 1;
      break;
    case 20:
      snapshot("scale-1");
      break;
    case 22:
      projectorScale(sandbox);
      break;
    case 30:
      snapshot("scale-2");
      break;
    case 32:
      SDL_GetWindowSize(window, &width_, &height_);
      SDL_SetWindowSize(window, width_ * 3 / 4, height_ * 3 / 4);
      break;
    case 42:
      snapshot("resized");
      break;
    case 44:
      SDL_SetWindowSize(window, width_, height_);
      break;
    case 52:
      sandbox.open(nextScene(sandbox.sceneName));  // the Scene menu's choice
      break;
    case 60:
      snapshot("next-scene");
      break;
    case 62:
      key(SDLK_SPACE);
      break;
    case 68:
      snapshot("paused");
      break;
    case 70:
      key(SDLK_p);
      break;
    case 78:
      snapshot("panels");
      break;
    case 80:
      report_ = "{\"scenario\": \"present\", \"views\": " + jsonList(items_) + "}";
      return false;
    default:
      break;
  }
  return true;
}

bool LectureScript::graspQuiet(Sandbox& sandbox, int frame) {
  constexpr double kControlSeconds = 4;
  if (!sandbox.banner.empty()) {
    ++bannerFrames_;
    if (items_.empty() || items_.back() != jsonQuoted(sandbox.banner))
      items_.push_back(jsonQuoted(sandbox.banner));
  }
  if (frame == 2) {
    if (!startHandGrasp(sandbox)) {
      report_ = "{\"scenario\": \"grasp-quiet\", \"failure\": \"not the hand\"}";
      return false;
    }
  } else if (frame == 90) {  // "click empty space": the nearest point 0.2 m or more from the box
    const World& world = *sandbox.world();
    const Vec2 box = world.body(world.findBody("box")).position;
    double best = 1e300;
    for (int i = -8; i <= 8; ++i)
      for (int j = -8; j <= 8; ++j) {
        const Vec2 p = box + 0.05 * Vec2(i, j);
        const double d = (p - box).norm();
        if (d < 0.2 || d >= best || sandbox.bodyAt(p, true) >= 0 ||
            sandbox.cableAt(p, 8 * sandbox.camera.metresPerPixel) >= 0)
          continue;
        best = d;
        to_ = sandbox.camera.toScreen(p);
      }
    target_ = sandbox.camera.toWorld(to_);
    mouse(SDL_MOUSEMOTION, to_);
    mouse(SDL_MOUSEBUTTONDOWN, to_);
    mouse(SDL_MOUSEBUTTONUP, to_);
  } else if (frame > 90 && sandbox.world()->time() >= 1.5 + kControlSeconds) {
    report_ = "{\"scenario\": \"grasp-quiet\", \"banner_frames\": " + jsonNumber(bannerFrames_) +
              ", \"banners\": " + jsonList(items_) +
              ", \"log_entries\": " + jsonNumber(sandbox.log.entries().size()) +
              ", \"state\": " + jsonQuoted(handGraspState(sandbox)) + ", \"clicked\": [" +
              jsonNumber(target_.x()) + ", " + jsonNumber(target_.y()) + "]" + ", \"target\": [" +
              jsonNumber(sandbox.target ? sandbox.target->x() : 1e9) + ", " +
              jsonNumber(sandbox.target ? sandbox.target->y() : 1e9) + "]" +
              ", \"time\": " + jsonNumber(sandbox.world()->time()) + "}";
    return false;
  }
  return true;
}

bool LectureScript::tensionRun(Sandbox& sandbox, int frame) {
  World& world = *sandbox.world();
  if (frame >= 1 && frame < 70) {
    lowest_ = std::min(lowest_, sandbox.tensionScale);
    highest_ = std::max(highest_, sandbox.tensionScale);
    for (int i = 0; i < world.cableCount(); ++i)
      largest_ = std::max(largest_, world.cable(i).tension());
  }
  if (frame == 5) {  // the body at a cable's end, pulled down hard
    body_ = bodyAtACableEnd(world);
    if (body_ < 0) {
      report_ = "{\"scenario\": \"tension-run\", \"failure\": \"no body at a cable's end\"}";
      return false;
    }
    from_ = sandbox.camera.toScreen(world.body(body_).position);
    to_ = from_ + Vec2(0, 250);
    mouse(SDL_MOUSEMOTION, from_);
    mouse(SDL_MOUSEBUTTONDOWN, from_);
  } else if (frame > 5 && frame <= 45) {
    mouse(SDL_MOUSEMOTION, from_ + (to_ - from_) * std::min(1.0, (frame - 5) / 20.0));
  } else if (frame == 46) {
    mouse(SDL_MOUSEBUTTONUP, to_);
  } else if (frame == 55) {
    key(SDLK_r);
  } else if (frame == 70) {
    items_.push_back("\"scene\": " + jsonQuoted(sandbox.sceneName) +
                     ", \"scene_scale\": " + jsonNumber(loadTensionScale(sandbox.scene)) +
                     ", \"lowest\": " + jsonNumber(lowest_) + ", \"highest\": " +
                     jsonNumber(highest_) + ", \"largest_tension\": " + jsonNumber(largest_));
    sandbox.tensionScaleLocked = true;                // the View section's checkbox
    sandbox.tensionScale = 2 * sandbox.tensionScale;  // and its "scale max (N)" field
    items_.push_back("\"locked_at\": " + jsonNumber(sandbox.tensionScale));
    sandbox.open(nextScene(sandbox.sceneName));
  } else if (frame == 75) {
    sandbox.reset();
  } else if (frame == 80) {
    report_ = "{\"scenario\": \"tension-run\", " + items_[0] + ", " + items_[1] +
              ", \"next_scene\": " + jsonQuoted(sandbox.sceneName) +
              ", \"next_scene_scale\": " + jsonNumber(loadTensionScale(sandbox.scene)) +
              ", \"after_next_scene\": " + jsonNumber(sandbox.tensionScale) +
              ", \"locked\": " + (sandbox.tensionScaleLocked ? "true" : "false") + "}";
    return false;
  }
  return true;
}

}  // namespace cablelab::ui

namespace cablelab::ui {

bool LectureScript::walkthrough(Sandbox& sandbox, int frame) {
  recordPendingView(sandbox);
  auto snapshot = [&](const char* name) { this->snapshot(sandbox, name); };
  World& world = *sandbox.world();
  if (frame >= 10 && frame <= 600) watchFollow(sandbox);  // the run untouched
  if (frame == 1) {
    projectorScale(sandbox);
  } else if (frame == 3) {
    key(SDLK_p);
  } else if (frame == 10) {
    snapshot("start");
  } else if (frame == 180) {
    snapshot("run-3s");
  } else if (frame == 600) {
    snapshot("run-10s");
  } else if (frame == 605) {  // drag the body at a cable's end sideways and down
    body_ = bodyAtACableEnd(world);
    if (body_ >= 0) {
      from_ = sandbox.camera.toScreen(world.body(body_).position);
      to_ = from_ + Vec2(120, 120);
      mouse(SDL_MOUSEMOTION, from_);
      mouse(SDL_MOUSEBUTTONDOWN, from_);
    }
  } else if (frame > 605 && frame < 650 && body_ >= 0) {
    mouse(SDL_MOUSEMOTION, from_ + (to_ - from_) * std::min(1.0, (frame - 605) / 20.0));
    if (frame == 640) snapshot("dragging");
  } else if (frame == 650 && body_ >= 0) {
    mouse(SDL_MOUSEBUTTONUP, to_);
  } else if (frame == 720) {
    snapshot("dropped");
  } else if (frame == 725) {
    tryStep(sandbox);
  } else if (frame == 900) {
    snapshot("try-step");
  } else if (frame == 902) {
    key(SDLK_SPACE);
  } else if (frame == 910) {
    snapshot("paused");
  } else if (frame > 912 && frame <= 972) {
    key(SDLK_b);
  } else if (frame == 980) {
    snapshot("rewound");
  } else if (frame == 982) {
    key(SDLK_SPACE);
  } else if (frame == 1100) {
    snapshot("play-on");
  } else if (frame == 1102 && sandbox.sceneName == "capstan") {  // its second slider step
    auto values = sandbox.parameters;
    for (auto& [k, v] : values)
      if (k == "turns") v = 2;
    sandbox.rebuild(values);
  } else if (frame == 1130 && sandbox.sceneName == "capstan") {  // half a second on
    snapshot("turns");
  } else if (frame == (sandbox.sceneName == "capstan" ? 1132 : 1102)) {
    report_ = "{\"scenario\": \"walkthrough\", \"banner\": " + jsonQuoted(sandbox.banner) +
              ", \"views\": " + jsonList(items_) + ", " + followJson() + "}";
    return false;
  }
  return true;
}

}  // namespace cablelab::ui

namespace cablelab::ui {

bool LectureScript::selectRope(Sandbox& sandbox, int frame) {
  if (frame == 5) {
    items_.push_back(std::string("\"open_before\": ") + (sandbox.inspectorOpen ? "true" : "false"));
    // A point of a cable (none of a body) in the view, as the user clicks it.
    const PanelRect f = sandbox.freeArea();
    bool found = false;
    for (float y = f.y + 4; y < f.y + f.height && !found; y += 3)
      for (float x = f.x + 4; x < f.x + f.width && !found; x += 3) {
        const Vec2 p = sandbox.camera.toWorld(Vec2(x, y));
        if (sandbox.bodyAt(p, true) >= 0) continue;
        body_ = sandbox.cableAt(p, 2 * sandbox.camera.metresPerPixel);
        if (body_ >= 0) {
          from_ = Vec2(x, y);
          found = true;
        }
      }
    if (!found) {
      report_ = "{\"scenario\": \"select-rope\", \"failure\": \"no cable in view\"}";
      return false;
    }
    sandbox.selectedCable = -1;
    mouse(SDL_MOUSEMOTION, from_);
    mouse(SDL_MOUSEBUTTONDOWN, from_);
    mouse(SDL_MOUSEBUTTONUP, from_);
    // A lecture's plots beside it: a body's height and the rope's tension, each a chart (the
    // Plots section opens with its first chart).
    const auto quantities = availableQuantities(*sandbox.world(), -1);
    for (const Quantity::Kind kind : {Quantity::Kind::Y, Quantity::Kind::Tension})
      for (const Quantity& q : quantities)
        if (q.kind == kind) {
          sandbox.plots->addCurve(sandbox.plots->charts.size(), q);
          break;
        }
  } else if (frame == 13) {
    snapshot(sandbox, "clicked");
  } else if (frame == 15) {
    report_ = "{\"scenario\": \"select-rope\", " + items_[0] +
              ", \"clicked_cable\": " + jsonNumber(body_) +
              ", \"selected_cable\": " + jsonNumber(sandbox.selectedCable) +
              ", \"open_after\": " + (sandbox.inspectorOpen ? "true" : "false") +
              ", \"plots_open\": " + (sandbox.plotsSectionOpen ? "true" : "false") +
              ", \"overflow\": " + jsonNumber(sandbox.panelOverflow[1]) +
              ", \"simulation_overflow\": " + jsonNumber(sandbox.panelOverflow[0]) + "}";
    return false;
  }
  return true;
}

}  // namespace cablelab::ui

namespace cablelab::ui {

bool LectureScript::tour(Sandbox& sandbox, int frame) {
  // The built-in scenes the walkthrough tests do not walk (tests/ui/lecture_gui_test.cpp).
  static const std::vector<std::string> kScenes = {"ballast", "pulley", "hexagon", "membrane",
                                                   "hand"};
  constexpr int kFramesPerScene = 100;
  recordPendingView(sandbox);
  if (frame == 1) {
    projectorScale(sandbox);
    key(SDLK_p);
    return true;
  }
  const int k = (frame - 2) / kFramesPerScene, f = (frame - 2) % kFramesPerScene;
  if (k >= static_cast<int>(kScenes.size())) {
    report_ = "{\"scenario\": \"tour\", \"banners\": " + jsonList(banners_) +
              ", \"views\": " + jsonList(items_) + "}";
    return false;
  }
  const std::string& scene = kScenes[k];
  if (f > 0 && !sandbox.banner.empty() &&
      (banners_.empty() || banners_.back() != jsonQuoted(scene + ": " + sandbox.banner)))
    banners_.push_back(jsonQuoted(scene + ": " + sandbox.banner));
  SDL_Window* window = SDL_GetWindowFromID(windowId_);
  const FurnitureLayout& furniture = sandbox.drawn.furniture;
  const auto shot = [&](const char* what) {
    shotName_ = scene + "-" + what;
    snapshot(sandbox, shotName_.c_str());
  };
  if (f == 0) {
    SDL_SetWindowSize(window, 1280, 720);
    sandbox.open(scene);  // the Scene menu's choice
  } else if (f == 8) {
    shot("720-start");
  } else if (f == 10) {  // drag the body at a cable's end (the membrane's weighted point)
    const World& world = *sandbox.world();
    body_ = bodyAtACableEnd(world);
    for (int i = 0; i < world.bodyCount() && body_ < 0; ++i)
      if (world.scene().bodies[i].type == BodyType::Dynamic) body_ = i;
    if (body_ >= 0) {
      from_ = sandbox.camera.toScreen(sandbox.world()->body(body_).position);
      to_ = scene == "hexagon" && !furniture.colourBar.empty() ? middle(furniture.colourBar)
                                                               : from_ + Vec2(120, 120);
      mouse(SDL_MOUSEMOTION, from_);
      mouse(SDL_MOUSEBUTTONDOWN, from_);
    }
  } else if (f > 10 && f <= 20 && body_ >= 0) {
    mouse(SDL_MOUSEMOTION, from_ + (to_ - from_) * ((f - 10) / 10.0));
  } else if (f == 22 && body_ >= 0) {
    shot("720-drag");
  } else if (f > 22 && f <= 32 && scene == "hexagon" && !furniture.scaleBar.empty()) {
    // on along the bottom onto the scale bar
    mouse(SDL_MOUSEMOTION, to_ + (middle(furniture.scaleBar) - to_) * ((f - 22) / 10.0));
    if (f == 32) to_ = middle(furniture.scaleBar);
  } else if (f == 34 && scene == "hexagon") {
    shot("720-drag-scale-bar");
  } else if (f == 36 && body_ >= 0) {
    mouse(SDL_MOUSEBUTTONUP, to_);
  } else if (f == 38 && scene == "membrane") {  // "select the band (click it)"
    from_ = cablePixel(sandbox);
    mouse(SDL_MOUSEMOTION, from_);
    mouse(SDL_MOUSEBUTTONDOWN, from_);
    mouse(SDL_MOUSEBUTTONUP, from_);
  } else if (f == 38) {
    tryStep(sandbox);
  } else if ((f == 1 || f == 61) && scene == "pulley") {  // a clip of the run, then stop by
    from_ = middle(sandbox.recordButton);  // the strip's Record button: pointer, press, release
    movePointer(windowId_, from_);  // Dear ImGui reads a held button's pointer from the screen
  } else if ((f == 2 || f == 62) && scene == "pulley") {
    mouse(SDL_MOUSEBUTTONDOWN, from_);
  } else if ((f == 3 || f == 63) && scene == "pulley") {
    mouse(SDL_MOUSEBUTTONUP, from_);
  } else if ((f == 4 || f == 64) && scene == "pulley") {  // off the button: the next press in
    const PanelRect v = sandbox.freeArea();               // the view would be its click
    movePointer(windowId_, Vec2(v.x + 4, v.y + 0.5 * v.height));
  } else if (f == 6 && scene == "pulley") {
    shot("720-recording");
  } else if (f == 66) {
    shot("720-try");
  } else if (f == 68) {
    key(SDLK_SPACE);
  } else if (f == 72) {
    shot("720-paused");
  } else if (f == 74) {
    SDL_SetWindowSize(window, 1920, 1080);
  } else if (f == 84) {
    shot("1080-paused");
  } else if (f == 86) {
    key(SDLK_SPACE);
  } else if (f == 98) {
    shot("1080-run");
  }
  return true;
}

bool LectureScript::laptop(Sandbox& sandbox, int frame) {
  constexpr int kFramesPerScene = 12;  // the fit is due once the panels are laid out
  recordPendingView(sandbox);
  const auto all = builtinSceneList();
  const int k = (frame - 2) / kFramesPerScene, f = (frame - 2) % kFramesPerScene;
  if (frame < 2) return true;
  if (k >= static_cast<int>(all.size())) {
    report_ = "{\"scenario\": \"laptop\", \"views\": " + jsonList(items_) + "}";
    return false;
  }
  if (f == 0) sandbox.open(all[k].name);  // the Scene menu's choice
  if (f == kFramesPerScene - 2) {
    shotName_ = all[k].name;
    snapshot(sandbox, shotName_.c_str());
  }
  return true;
}

bool LectureScript::handExport(Sandbox& sandbox, int frame) {
  constexpr int kRunFrames = 150;  // 2.5 s of history at 60 Hz
  const HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  if (!h) {
    report_ = "{\"scenario\": \"hand-export\", \"failure\": \"not the hand\"}";
    return false;
  }
  if (frame < kRunFrames) return true;
  const PanelRect& b = h->exportPngButton;
  const Vec2 centre(b.x + 0.5 * b.width, b.y + 0.5 * b.height);
  if ((clickStage_ == 2 && sandbox.message.rfind("saved", 0) == 0) || frame > kRunFrames + 120) {
    const PanelRect free = sandbox.freeArea();
    report_ = "{\"scenario\": \"hand-export\", \"message\": " + jsonQuoted(sandbox.message) +
              ", \"error\": " + jsonQuoted(sandbox.error) +
              ", \"tension_scale\": " + jsonNumber(sandbox.tensionScale) +
              ", \"plot_labels\": " + plotLabels_ +
              ", \"plots_screenshot\": " + jsonQuoted(out_ + "-thumbnails.png") + ", \"free\": [" +
              jsonNumber(free.x) + ", " + jsonNumber(free.y) + ", " + jsonNumber(free.width) +
              ", " + jsonNumber(free.height) + "]}";
    return false;
  }
  if (clickStage_ == 1) {  // pressed last frame: let go (Dear ImGui needs two frames for a click)
    mouse(SDL_MOUSEBUTTONUP, centre);
    clickStage_ = 2;
    return true;
  }
  if (clickStage_ == 2) return true;  // clicked: wait for the files
  // The button below the panel's fold (projector scale): the wheel over the panel scrolls down.
  const PanelRect free = sandbox.freeArea();
  if (b.height <= 0 || b.y + b.height > free.y + free.height - 4) {
    movePointer(windowId_, Vec2(0.5 * free.x, free.y + 0.5 * free.height));
    SDL_Event wheel{};
    wheel.type = SDL_MOUSEWHEEL;
    wheel.wheel.windowID = windowId_;
    wheel.wheel.y = -2;
    SDL_PushEvent(&wheel);
    return true;
  }
  if (plotLabels_.empty() && pointerAway_ < 10) {  // the pointer off the plots (no tooltip)
    movePointer(windowId_, Vec2(free.x + 0.5 * free.width, free.y + 0.5 * free.height));
    ++pointerAway_;
    return true;
  }
  if (plotLabels_.empty()) {  // the thumbnails in view above the button: their picture first
    std::vector<std::string> rects;
    for (const PanelRect& r : h->plotLabels)
      rects.push_back("[" + jsonNumber(r.x) + ", " + jsonNumber(r.y) + ", " +
                      jsonNumber(r.x + r.width) + ", " + jsonNumber(r.y + r.height) + "]");
    plotLabels_ = jsonList(rects);
    snapshot(sandbox, "thumbnails");
    return true;
  }
  movePointer(windowId_, centre);
  mouse(SDL_MOUSEBUTTONDOWN, centre);
  sandbox.message.clear();  // the screenshot's "saved": the export's comes next
  clickStage_ = 1;
  return true;
}

}  // namespace cablelab::ui

namespace cablelab::ui {

bool LectureScript::firstMechanism(Sandbox& sandbox, int) {
  if (!first_) first_ = std::make_unique<FirstMechanismScript>(windowId_, out_);
  if (first_->beforeFrame(sandbox)) return true;
  report_ = first_->report();
  return false;
}

}  // namespace cablelab::ui

namespace cablelab::ui {

void LectureScript::watchFollow(const Sandbox& sandbox) {
  // m/s: a body this fast moves; a turn counts as its speed at 0.2 m (ui/demo_loop.cpp)
  constexpr double kMoving = 0.05;
  const World& world = *sandbox.world();
  const PanelRect free = sandbox.freeArea();
  bool moving = false, seen = false;
  for (int i = 0; i < world.bodyCount(); ++i) {
    if (world.scene().bodies[i].type != BodyType::Dynamic) continue;
    const BodyState& b = world.body(i);
    if (std::max(b.velocity.norm(), 0.2 * std::abs(b.angularVelocity)) < kMoving) continue;
    moving = true;
    seen |= free.contains(sandbox.camera.toScreen(world.body(i).position));
  }
  movingFrames_ += moving;
  movingOutOfViewFrames_ += moving && !seen;
  // The body the close-up followed down (the tackle's effort weight), at rest out of view (the
  // view lags a falling body by a few frames).
  const int followed = sandbox.demo.closeUpBody;
  if (sandbox.closeUp && followed >= 0 && followed < world.bodyCount() &&
      world.body(followed).velocity.norm() < kMoving)
    followedOutOfViewFrames_ +=
        !free.contains(sandbox.camera.toScreen(world.body(followed).position));
  const double scale = sandbox.camera.metresPerPixel;
  const bool sameRun = lastScale_ > 0 && sandbox.demo.restarts == lastRestarts_;
  if (sameRun)
    largestZoomStep_ = std::max(largestZoomStep_, std::max(scale / lastScale_, lastScale_ / scale));
  // Zooming back in is the view's return in the first second of a run (a restart), else a jump.
  const bool returning = !sameRun || world.time() < 1.0;
  widestInRun_ = returning ? scale : std::max(widestInRun_, scale);
  largestZoomIn_ = std::max(largestZoomIn_, widestInRun_ / scale);
  lastScale_ = scale;
  lastRestarts_ = sandbox.demo.restarts;
}

std::string LectureScript::followJson() const {
  return "\"largest_zoom_step\": " + jsonNumber(largestZoomStep_) +
         ", \"largest_zoom_in\": " + jsonNumber(largestZoomIn_) +
         ", \"moving_frames\": " + jsonNumber(movingFrames_) +
         ", \"moving_out_of_view_frames\": " + jsonNumber(movingOutOfViewFrames_) +
         ", \"followed_out_of_view_frames\": " + jsonNumber(followedOutOfViewFrames_) +
         ", \"restarts\": " + jsonNumber(lastRestarts_);
}

bool LectureScript::follow(Sandbox& sandbox, int frame) {
  constexpr int kStart = 10, kFrames = 25 * 60;  // 25 s at the scenes' 60 steps a second
  recordPendingView(sandbox);
  if (frame == 1) projectorScale(sandbox);
  if (frame == 3) key(SDLK_p);
  if (frame < kStart) return true;
  watchFollow(sandbox);
  for (const int s : {1, 4, 6, 10, 20})
    if (frame == kStart + 60 * s) snapshot(sandbox, ("run-" + std::to_string(s) + "s").c_str());
  if (frame < kStart + kFrames) return true;
  report_ = "{\"scenario\": \"follow\", \"views\": " + jsonList(items_) + ", " + followJson() + "}";
  return false;
}

}  // namespace cablelab::ui
