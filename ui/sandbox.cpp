#include "ui/sandbox.h"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "engine/core/error.h"
#include "ui/colormap.h"
#include "ui/controller_panel.h"
#include "ui/scene_catalog.h"

namespace cablelab::ui {

Sandbox::Sandbox(int width, int height) {
  camera.width = width;
  camera.height = height;
}

Sandbox::~Sandbox() = default;

bool Sandbox::open(const std::string& nameOrPath) {
  try {
    SceneDef def = loadScene(nameOrPath);
    auto fresh = std::make_unique<World>(def, nameOrPath);
    scene = std::move(def);
    sceneName = nameOrPath;
    dt = scene.dt;
    substeps = scene.substeps;
    gravity = scene.gravity;
    world_ = std::move(fresh);
    camera = Camera::fit(scene.view, camera.width, camera.height);
    target.reset();
    gesture = {};
    selectedCable = world_->cableCount() > 0 ? 0 : -1;
    selectedBody = -1;
    tensionHistory.assign(world_->cableCount(), std::vector<float>(kHistory, 0.0f));
    historyHead = 0;
    tensionScale = 1;
    accumulator_ = 0;
    loadCableEdit();
    controller.reset();
    controllerOpened(*this);
    error.clear();
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    std::cerr << "cablelab-gui: cannot open " << nameOrPath << ": " << e.what() << "\n";
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
    gesture = {};
    for (auto& h : tensionHistory) std::fill(h.begin(), h.end(), 0.0f);
    historyHead = 0;
    accumulator_ = 0;
    loadCableEdit();
    controllerOpened(*this);
  } catch (const std::exception& e) {
    error = e.what();
    std::cerr << "cablelab-gui: reset failed: " << e.what() << "\n";
  }
}

void Sandbox::advance(double frameSeconds, bool fixedStep) {
  if (!world_) return;
  int steps = 0;
  if (paused) {
    steps = std::min(pendingSteps, 8);
    pendingSteps -= steps;
    accumulator_ = 0;
  } else if (fixedStep) {
    steps = 1;
  } else {
    accumulator_ = std::min(accumulator_ + frameSeconds, 8 * dt);
    steps = static_cast<int>(accumulator_ / dt);
    accumulator_ -= steps * dt;
  }
  try {
    if (world_->gravity() != gravity) world_->setGravity(gravity);
    for (int i = 0; i < steps; ++i) {
      controllerBeforeStep(*this, *world_);
      world_->step(dt, substeps);
      afterStep();
    }
  } catch (const std::exception& e) {
    paused = true;
    error = std::string("simulation stopped: ") + e.what();
    std::cerr << "cablelab-gui: " << error << "\n";
  }
}

void Sandbox::afterStep() {
  controllerAfterStep(*this, *world_);
  for (int i = 0; i < world_->cableCount() && i < static_cast<int>(tensionHistory.size()); ++i) {
    const double t = world_->cable(i).tension();
    tensionHistory[i][historyHead] = std::isfinite(t) ? static_cast<float>(t) : 0.0f;
    if (std::isfinite(t) && t > tensionScale) tensionScale = niceCeil(t);
  }
  historyHead = (historyHead + 1) % kHistory;
}

int Sandbox::bodyAt(const Vec2& point) const {
  if (!world_) return -1;
  for (int i = world_->bodyCount() - 1; i >= 0; --i) {
    const BodyDef& def = world_->scene().bodies[i];
    if (def.type != BodyType::Dynamic) continue;
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
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    loadCableEdit();
    return false;
  }
}

Overlay Sandbox::overlay() const {
  Overlay o;
  if (target) o.targets.push_back({*target, "target", {0.85f, 0.1f, 0.55f, 1.0f}});
  if (world_ && world_->draggedBody() >= 0) {
    const BodyState& s = world_->body(world_->draggedBody());
    o.arrows.push_back({s.position + rotate(gesture.grabLocal, s.angle),
                        world_->dragTarget(),
                        "",
                        {0.2f, 0.2f, 0.2f, 1.0f}});
  }
  controllerOverlay(*this, o);
  return o;
}

RenderOptions Sandbox::renderOptions() const {
  RenderOptions options;
  options.tensionScale = tensionScale;
  options.selectedCable = selectedCable;
  options.selectedBody = selectedBody;
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
  options.freeX = left;
  options.freeY = top;
  options.freeWidth = std::max(right - left, 0.0f);
  options.freeHeight = std::max(bottom - top, 0.0f);
  return options;
}

}  // namespace cablelab::ui
