#include "ui/sandbox.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "engine/core/error.h"
#include "ui/authoring.h"
#include "ui/colormap.h"
#include "ui/controller_panel.h"
#include "ui/plot_board.h"
#include "ui/plot_panel.h"
#include "ui/presentation.h"
#include "ui/scene_bounds.h"
#include "ui/scene_catalog.h"
#include "ui/tension_scale.h"
#include "ui/timeline.h"

namespace cablelab::ui {
namespace {

constexpr double kBannerSeconds = 6;  // a banner stays this long (wall time)
constexpr double kActionSeconds = 1;  // a warning this soon after a drag or edit is its doing
constexpr double kOverLength = 1e-5;  // m: a rigid cable longer than its rest length by more
                                      // is settled before a paused world runs again

const std::string kEdited = "edited-";  // sceneName's prefix for a scene changed in the window

/// An edit's validation error in the student's words: the scene file's path to a body, cable
/// or joint ("edited scene: bodies[1].mass: ...") by its name as the view labels it
/// ("box1: mass: ...").
std::string editErrorWithNames(std::string error, const SceneDef& def) {
  const std::string prefix = "edited scene: ";
  if (error.rfind(prefix, 0) == 0) error.erase(0, prefix.size());
  const auto name = [&](const std::string& list, size_t k) -> std::string {
    if (list == "bodies" && k < def.bodies.size()) return def.bodies[k].name;
    if (list == "cables" && k < def.cables.size()) return def.cables[k].name;
    if (list == "joints" && k < def.joints.size()) return def.joints[k].name;
    return "";
  };
  for (const std::string list : {"bodies", "cables", "joints"}) {
    const std::string open = list + "[";
    if (error.rfind(open, 0) != 0) continue;
    const size_t close = error.find("].", open.size());
    if (close == std::string::npos) break;
    const std::string shown = name(list, std::strtoul(error.c_str() + open.size(), nullptr, 10));
    if (!shown.empty()) error = shown + ": " + error.substr(close + 2);
    break;
  }
  return error;
}

/// A clicked cable's tension as the view's note says it in presentation mode (no Inspector):
/// "band: tension 4.01 N"; one value per span, start to end, where pulleys part it ("rope:
/// tensions 58.9, 19.6 N from its start", the capstan's two sides of the drum).
std::string tensionNote(const Cable& c) {
  char value[32];
  std::string text = c.name() + (c.spanCount() > 1 ? ": tensions " : ": tension ");
  for (int k = 0; k < c.spanCount(); ++k) {
    std::snprintf(value, sizeof value, "%s%.3g", k ? ", " : "", c.spanTension(k));
    text += value;
  }
  return text + (c.spanCount() > 1 ? " N from its start" : " N");
}

}  // namespace

Sandbox::Sandbox(int width, int height) {
  camera.width = width;
  camera.height = height;
  draw.markerLegend = true;
  authoring = std::make_unique<Authoring>();
  timeline = std::make_unique<Timeline>();
  plots = std::make_unique<PlotBoard>();
}

Sandbox::~Sandbox() = default;

bool Sandbox::adopt(SceneDef def, const std::string& name, bool fitCamera) {
  auto fresh = std::make_unique<World>(def, name);
  if (name != sceneName || watchedCable >= fresh->cableCount()) watchedCable = -1;
  scene = std::move(def);
  sceneName = name;
  dt = scene.dt;
  substeps = scene.substeps;
  gravity = scene.gravity;
  world_ = std::move(fresh);
  if (fitCamera) {
    camera = Camera::fit(scene.view, camera.width, camera.height);
    fitPending = true;
  }
  target.reset();
  gesture = {};
  drag = {};
  selectedCable = world_->cableCount() > 0 ? 0 : -1;
  selectedBody = -1;
  follow = false;
  demo = startDemo(scene, name);
  tensionHistory.assign(world_->cableCount(), std::vector<float>(kHistory, 0.0f));
  historyHead = 0;
  sceneTensionScale = loadTensionScale(scene);
  if (!tensionScaleLocked) tensionScale = sceneTensionScale;
  accumulator_ = 0;
  log.newWorld();
  banner.clear();
  timeline->clear();
  plots->clear(true);
  actionUntil = -1;
  loadCableEdit();
  controller.reset();
  controllerOpened(*this);
  error.clear();
  return true;
}

bool Sandbox::open(const std::string& nameOrPath) {
  try {
    adopt(loadScene(nameOrPath), nameOrPath, true);
    sceneFile = isBuiltinScene(nameOrPath) ? "" : nameOrPath;
    paused = false;  // every scene starts running (a paused one said so only in small print)
    pendingSteps = 0;
    const Authoring::Tool tool = authoring->tool;
    authoring = std::make_unique<Authoring>();
    authoring->tool = tool;
    parameters.clear();
    for (const SceneParameter& p : sceneParameters(nameOrPath))
      parameters.emplace_back(p.name, p.value);
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    std::cerr << "cablelab-gui: cannot open " << nameOrPath << ": " << e.what() << "\n";
    return false;
  }
}

std::string Sandbox::displayName() const {
  if (!sceneFile.empty()) return std::filesystem::path(sceneFile).filename().string();
  if (sceneName.rfind(kEdited, 0) != 0) return sceneName;
  std::string name = scene.name.empty() ? "my mechanism" : scene.name;
  std::replace(name.begin(), name.end(), '_', ' ');
  return isBuiltinScene(scene.name) ? name + " (edited)" : name;
}

std::string Sandbox::fileStem() const {
  std::string stem = std::filesystem::path(displayName()).stem().string();
  std::replace(stem.begin(), stem.end(), ' ', '_');  // "hexagon (edited)": hexagon_edited
  std::erase(stem, '(');
  std::erase(stem, ')');
  return stem.empty() ? "scene" : stem;
}

bool Sandbox::rebuild(const std::vector<std::pair<std::string, double>>& values) {
  try {
    const Camera keep = camera;
    const double scale = sceneTensionScale;
    adopt(loadScene(sceneName, values), sceneName, false);
    camera = keep;
    // A lighter load keeps the scale, so that the runs before and after the slider compare by
    // colour (the tackle's went from 0..100 N to 0..50 N); a heavier one grows it.
    sceneTensionScale = std::max(scale, sceneTensionScale);
    if (!tensionScaleLocked) tensionScale = sceneTensionScale;
    // A fitted view is fitted again to the new run (a demo's stage changes with its loads);
    // a view the user chose stays (ui/presentation.h).
    if (viewFitted) fitPending = true;
    parameters = values;
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    std::cerr << "cablelab-gui: " << e.what() << "\n";
    return false;
  }
}

bool Sandbox::replaceScene(const SceneDef& def) {
  try {
    validateScene(def, "edited scene");
    // An edited scene is no longer the built-in one: its --set sliders no longer apply.
    const std::string base = def.name.empty() ? "scene" : def.name;
    adopt(def, base.rfind(kEdited, 0) == 0 ? base : kEdited + base, false);
    parameters.clear();
    return true;
  } catch (const std::exception& e) {
    error = editErrorWithNames(e.what(), def);
    return false;
  }
}

void Sandbox::reset() {
  if (scene.bodies.empty() && !world_) return;
  try {
    SceneDef def = scene;
    def.dt = dt;
    def.substeps = substeps;
    def.gravity = gravity;
    world_ = std::make_unique<World>(def, sceneName);
    demo.moved = false;
    demo.endedFor = 0;
    demo.closeUpBody = -1;
    gesture = {};
    drag = {};
    for (auto& h : tensionHistory) std::fill(h.begin(), h.end(), 0.0f);
    historyHead = 0;
    if (!tensionScaleLocked) tensionScale = sceneTensionScale;
    accumulator_ = 0;
    log.newWorld();
    banner.clear();
    timeline->clear();
    plots->clear(false);
    actionUntil = -1;
    loadCableEdit();
    controllerOpened(*this);
  } catch (const std::exception& e) {
    error = e.what();
    std::cerr << "cablelab-gui: reset failed: " << e.what() << "\n";
  }
}

void Sandbox::advance(double frameSeconds, bool fixedStep) {
  clock += frameSeconds;
  if (!world_) return;
  int steps = 0;
  if (paused) {
    steps = std::min(pendingSteps, 8);
    pendingSteps -= steps;
    accumulator_ = 0;
  } else if (fixedStep) {
    steps = 1;
  } else {
    accumulator_ = std::min(accumulator_ + speed * frameSeconds, 8 * dt);
    steps = static_cast<int>(accumulator_ / dt);
    accumulator_ -= steps * dt;
  }
  try {
    if (world_->gravity() != gravity) world_->setGravity(gravity);
    // Settle only after an edit while paused: a pause alone changes nothing (a rewound run
    // plays on exactly).
    if (steps > 0 && wasPaused_ && world_->history().inputs().size() != inputsAfterStep_)
      settleBeforeRunning();
    wasPaused_ = paused;
    for (int i = 0; i < steps; ++i) {
      controllerBeforeStep(*this, *world_);
      applyDrag();
      world_->step(dt, substeps);
      inputsAfterStep_ = world_->history().inputs().size();
      afterStep();
      if (demo.loops && drag.body < 0 && runEnded(demo, *world_, dt)) {
        restartDemo();
        break;
      }
    }
  } catch (const std::exception& e) {
    paused = true;
    error = std::string("simulation stopped: ") + e.what();
    std::cerr << "cablelab-gui: " << error << "\n";
  }
  checkWarnings();
  // A scripted run steps one dt a frame, and its camera follows at the same pace: the views it
  // checks do not depend on how fast the machine draws.
  followCloseUp(*this, fixedStep ? dt : frameSeconds);
  if (follow && selectedBody >= 0 && selectedBody < world_->bodyCount())
    camera.center = centreFor(world_->body(selectedBody).position);
}

void Sandbox::restartDemo() {
  const int restarts = demo.restarts + 1;
  reset();
  demo.restarts = restarts;
  // While a clip records, its notice stays: the clip goes on through the new run (ui/recorder.h).
  if (!recording)
    message = "The run has ended, so it starts again (run " + std::to_string(restarts + 1) + ").";
}

void Sandbox::checkWarnings() {
  if (drag.body >= 0 && drag.body < world_->bodyCount()) {
    action = {UserAction::Kind::Drag, world_->scene().bodies[drag.body].name};
    actionUntil = clock + kActionSeconds;
  }
  const UserAction current = clock <= actionUntil ? action : UserAction{};
  for (const std::string& w : log.take(*world_, sceneName)) {
    const std::string plain = plainBanner(w, current);
    if (plain.empty()) continue;
    banner = plain;
    bannerUntil = clock + kBannerSeconds;
  }
  if (clock > bannerUntil) banner.clear();
}

void Sandbox::afterStep() {
  controllerAfterStep(*this, *world_);
  timelineAfterStep(*this);
  plotsAfterStep(*this);
  for (int i = 0; i < world_->cableCount() && i < static_cast<int>(tensionHistory.size()); ++i) {
    const double t = world_->cable(i).tension();
    tensionHistory[i][historyHead] = std::isfinite(t) ? static_cast<float>(t) : 0.0f;
  }
  historyHead = (historyHead + 1) % kHistory;
}

void Sandbox::adoptRewound(std::unique_ptr<World> world) {
  if (world) world_ = std::move(world);
  gesture = {};
  drag = {};
  accumulator_ = 0;
  inputsAfterStep_ = world_->history().inputs().size();
  log.takenAlready(*world_);
  banner.clear();
  loadCableEdit();
}

double Sandbox::dragLimit(int body) const {
  if (!world_ || body < 0 || body >= world_->bodyCount()) return 0;
  const double g = std::max(9.81, world_->gravity().norm());
  return dragWeights * world_->scene().bodies[body].mass * g;
}

void Sandbox::applyDrag() {
  if (drag.body < 0 || drag.body >= world_->bodyCount()) return;
  const BodyState& s = world_->body(drag.body);
  const Vec2 r = rotate(drag.grabLocal, s.angle);
  const Vec2 point = s.position + r;
  const Vec2 velocity = s.velocity + s.angularVelocity * Vec2(-r.y(), r.x());
  const double m = world_->scene().bodies[drag.body].mass;
  const double omega = 2 * M_PI * drag.hz;
  Vec2 force =
      m * (omega * omega * (drag.target - point) - 2 * drag.dampingRatio * omega * velocity);
  const double limit = dragLimit(drag.body);
  drag.limited = force.norm() > limit;
  if (drag.limited) force *= limit / force.norm();
  drag.force = force;
  world_->applyForce(drag.body, force, point);
}

void Sandbox::beginDrag(int body, const Vec2& worldPoint) {
  if (!world_ || body < 0 || body >= world_->bodyCount()) return;
  const BodyState& s = world_->body(body);
  drag = {};
  drag.body = body;
  drag.target = worldPoint;
  drag.grabLocal = rotate(worldPoint - s.position, -s.angle);
}

void Sandbox::dragTo(const Vec2& worldPoint, bool payOut) {
  if (!world_ || drag.body < 0) return;
  drag.target = worldPoint;
  if (!paused) return;
  // Paused: pose the body, grabbed point towards the mouse as far as its cables allow, at rest.
  sayPose(world_->poseBody(drag.body, drag.grabLocal, worldPoint, payOut));
}

// The status line says, in plain words, what held the body back or how much cable went out.
void Sandbox::sayPose(const PoseResult& pose) {
  constexpr double kHeldPixels = 3;  // a pose this far short of the mouse was held back
  const std::string body = "'" + world_->scene().bodies[drag.body].name + "'";
  char text[160];
  if (!pose.paidOut.empty()) {
    const Cable& c = world_->cable(pose.paidOut.front().first);
    std::snprintf(text, sizeof text, "cable '%s' let out to %.4g m (Shift held)", c.name().c_str(),
                  c.restLength());
    message = text;
    loadCableEdit();  // the Inspector shows the new rest length
  } else if (pose.miss > kHeldPixels * camera.metresPerPixel) {
    if (!pose.taut.empty())
      message = body + " can go no further: cable '" + world_->cable(pose.taut.front()).name() +
                "' is pulled tight (hold Shift while dragging to let it out)";
    else
      message = body + " can go no further: its joints hold it";
  } else if (message.find(" can go no further") != std::string::npos) {
    message.clear();
  }
}

// A paused world runs again: no rigid cable may start over its rest length (an edit while
// paused could leave one so), or it would snap back and fling what hangs on it.
void Sandbox::settleBeforeRunning() {
  for (int i = 0; i < world_->cableCount(); ++i) {
    const Cable& c = world_->cable(i);
    for (int k = 0; k < c.spanCount() && !c.elastic(); ++k)
      if (c.spanStretch(k) > kOverLength) {
        world_->settlePose();
        return;
      }
  }
}

void Sandbox::endDrag() {
  drag = {};
}

bool Sandbox::building() const {
  return authoring && authoring->tool != Authoring::Tool::None;
}

bool Sandbox::hasController() const {
  return controller && controller->hand;
}

int Sandbox::bodyAt(const Vec2& point, bool anyType) const {
  if (!world_) return -1;
  for (int i = world_->bodyCount() - 1; i >= 0; --i) {
    const BodyDef& def = world_->scene().bodies[i];
    if (!anyType && def.type != BodyType::Dynamic) continue;
    const BodyState& s = world_->body(i);
    const Vec2 local = rotate(point - s.position, -s.angle);
    for (const ShapeDef& shape : def.shapes) {
      if (shape.kind == ShapeDef::Kind::Circle) {
        if ((local - shape.center).norm() <= shape.radius) return i;
        continue;
      }
      bool inside = shape.vertices.size() >= 3;
      for (size_t k = 0; k < shape.vertices.size() && inside; ++k) {
        const Vec2& a = shape.vertices[k];
        const Vec2& b = shape.vertices[(k + 1) % shape.vertices.size()];
        inside = cross(b - a, local - a) >= 0;
      }
      if (inside) return i;
    }
  }
  return -1;
}

int Sandbox::cableAt(const Vec2& point, double tolerance) const {
  if (!world_) return -1;
  int best = -1;
  double bestDistance = tolerance;
  for (int i = 0; i < world_->cableCount(); ++i) {
    const auto& path = world_->cable(i).path();
    for (size_t k = 1; k < path.size(); ++k) {
      const Vec2 a = path[k - 1].world, d = path[k].world - a;
      const double len2 = d.squaredNorm();
      const double u = len2 > 0 ? std::clamp((point - a).dot(d) / len2, 0.0, 1.0) : 0.0;
      const double distance = (a + u * d - point).norm();
      if (distance <= bestDistance) bestDistance = distance, best = i;
    }
  }
  return best;
}

void Sandbox::resize(int width, int height) {
  camera.width = std::max(width, 1);
  camera.height = std::max(height, 1);
}

void Sandbox::loadCableEdit() {
  if (!world_ || selectedCable < 0 || selectedCable >= world_->cableCount()) return;
  const Cable& c = world_->cable(selectedCable);
  cableEdit = {c.restLength(), c.stiffness(), c.preload(), c.damping()};
}

bool Sandbox::applyCableEdit() {
  if (!world_ || selectedCable < 0 || selectedCable >= world_->cableCount()) return false;
  try {
    world_->setCableParameters(selectedCable, cableEdit.restLength, cableEdit.stiffness,
                               cableEdit.preload, cableEdit.damping);
    action = {UserAction::Kind::CableEdit, ""};
    actionUntil = clock + kActionSeconds;
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    loadCableEdit();
    return false;
  }
}

Overlay Sandbox::overlay() const {
  Overlay o;
  constexpr Colour kTarget{0.85f, 0.1f, 0.55f, 1.0f};
  if (target) {
    o.targets.push_back({*target, "target", kTarget});
    o.keys.push_back({Overlay::Key::Marker::Cross, "controller target", kTarget});
  }
  if (world_ && drag.body >= 0 && drag.body < world_->bodyCount()) {
    const BodyState& s = world_->body(drag.body);
    const Colour c = drag.limited ? Colour{0.85f, 0.1f, 0.1f, 1} : Colour{0.2f, 0.2f, 0.2f, 1};
    char text[64];
    std::snprintf(text, sizeof text, "%.3g N%s", drag.force.norm(), drag.limited ? " (limit)" : "");
    o.arrows.push_back(
        {s.position + rotate(drag.grabLocal, s.angle), drag.target, paused ? "pose" : text, c});
    o.keys.push_back({Overlay::Key::Marker::Arrow,
                      paused         ? "pose (paused)"
                      : drag.limited ? "drag, at its force limit"
                                     : "drag",
                      c});
  }
  controllerOverlay(*this, o);
  authoringOverlay(*this, o);
  // The hand's bodies collide with nothing (the model is its cables): say so, or a box sliding
  // through a paddle that looks solid reads as a bug.
  if (hasController())
    o.notes.push_back("The bodies pass through each other: only the bands hold the box.");
  if (presentation && world_ && watchedCable >= 0 && watchedCable < world_->cableCount())
    o.notes.push_back(tensionNote(world_->cable(watchedCable)));
  o.banner = banner;
  return o;
}

PanelRect Sandbox::freeArea() const {
  // The free area between the side panels (see panels.cpp for their layout).
  float left = 0, right = static_cast<float>(camera.width), top = 0;
  float bottom = static_cast<float>(camera.height);
  for (const PanelRect& p : panels) {
    if (p.x <= 1 && p.height > 0.5f * camera.height)
      left = std::max(left, p.x + p.width);
    else if (p.x + p.width >= camera.width - 1 && p.height > 0.5f * camera.height)
      right = std::min(right, p.x);
    else if (p.y <= 1 && p.width > 0.5f * camera.width)
      top = std::max(top, p.height);
    else if (p.y + p.height >= camera.height - 1 && p.width > 0.5f * camera.width)
      bottom = std::min(bottom, p.y);
  }
  return {left, top, std::max(right - left, 0.0f), std::max(bottom - top, 0.0f)};
}

Vec2 Sandbox::centreFor(const Vec2& p) const {
  const PanelRect f = freeArea();
  if (f.width < 1 || f.height < 1) return p;
  const double dx = f.x + 0.5 * f.width - 0.5 * camera.width;
  const double dy = f.y + 0.5 * f.height - 0.5 * camera.height;
  return p - Vec2(dx * camera.metresPerPixel, -dy * camera.metresPerPixel);
}

void Sandbox::fitView() {
  fitPending = false;
  const PanelRect f = freeArea();
  fittedArea = f;
  fittedScale = uiScale;
  fittedKeyRows = drawn.furniture.keyRows.size();
  viewFitted = true;
  fittedCanvas = showsCanvas(*this);
  if (!world_ || f.width < 40 || f.height < 40) return;
  closeUp = presentation && !fittedCanvas && wantsCloseUp(*this);
  if (presentation && !fittedCanvas) {
    camera = presentationFit(*this, f);
    return;
  }
  // The scene's view grown to hold the moving parts, above the bars' row; in presentation mode
  // too while a student builds (ui/presentation.h, showsCanvas).
  // Below a collapsed side panel's title bar too (the tackle's pulleys were under the
  // Inspector's).
  const float titleBar = renderOptions().keyTop;
  PanelRect area = f;
  area.y += titleBar;
  area.height = std::max(40.0f, f.height - titleBar - barRowHeight(*this));
  const double aspect = area.width / area.height;
  const Vec2 half(0.5 * scene.view.height * aspect, 0.5 * scene.view.height);
  WorldBounds b = sceneBounds(*world_, 0.04 * scene.view.height);
  if (!demo.stage.empty()) {  // the whole run of a demo (ui/demo_loop.h)
    b.include(demo.stage.lo);
    b.include(demo.stage.hi);
  }
  b.include(scene.view.center - half);
  b.include(scene.view.center + half);
  camera.metresPerPixel =
      std::max((b.hi.x() - b.lo.x()) / area.width, (b.hi.y() - b.lo.y()) / area.height);
  const double dx = area.x + 0.5 * area.width - 0.5 * camera.width;
  const double dy = area.y + 0.5 * area.height - 0.5 * camera.height;
  camera.center = 0.5 * (b.lo + b.hi) - camera.metresPerPixel * Vec2(dx, -dy);
  if (!fittedCanvas) camera = clearOfKey(*this, camera, f, barRowHeight(*this));
}

RenderOptions Sandbox::renderOptions() const {
  RenderOptions options = draw;
  options.tensionScale = tensionScale;
  options.selectedCable = selectedCable;
  options.selectedBody = selectedBody;
  options.lineScale = projector ? 2.0f : 1.0f;
  options.paused = paused;
  options.keyGivesWay = presentation;
  options.tensionLocked = tensionScaleLocked;
  const PanelRect free = freeArea();
  options.freeX = free.x;
  options.freeY = free.y;
  options.freeWidth = free.width;
  options.freeHeight = free.height;
  for (const PanelRect& p : panels)  // a collapsed side panel's title bar, top right
    if (p.height < 0.25f * camera.height && p.y <= free.y + 1 && p.x + p.width >= camera.width - 1)
      options.keyTop = std::max(options.keyTop, p.y + p.height - free.y);
  return options;
}

}  // namespace cablelab::ui
