// Sandbox: the state the interactive app owns (scene, world, camera, selection, controller
// target, settings) and the simulation verbs the panels and the input handler call.
//
// Needs: the engine's public headers and ui/scene_catalog.h; no SDL, no GL. Panels
// (ui/panels.h) and input (ui/input.h) are plain functions over a Sandbox.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "ui/camera.h"
#include "ui/overlay.h"
#include "ui/renderer.h"

namespace cablelab::ui {

struct ControllerState;  // ui/controller_panel.h

/// Screen rectangle of a UI panel (px); the scene under it does not take mouse input.
struct PanelRect {
  float x = 0, y = 0, width = 0, height = 0;
  bool contains(const Vec2& p) const {
    return p.x() >= x && p.x() < x + width && p.y() >= y && p.y() < y + height;
  }
};

/// Mouse gesture in progress.
struct Gesture {
  enum class Kind { None, DragBody, Pan };
  Kind kind = Kind::None;
  Vec2 lastMouse = Vec2::Zero();  ///< px
  Vec2 grabLocal = Vec2::Zero();  ///< DragBody: grabbed point in the body frame (m)
};

class Sandbox {
 public:
  Sandbox(int width, int height);
  ~Sandbox();

  /// Loads a built-in scene or a scene file. On failure keeps the current scene, stores the
  /// message in `error`, prints it on stderr and returns false.
  bool open(const std::string& nameOrPath);
  /// Rebuilds the world from the loaded scene with the current dt, substeps and gravity.
  void reset();
  /// Advances the simulation for one displayed frame: one step of `dt` when `fixedStep`, else
  /// as many steps as `frameSeconds` of wall time holds (at most 8). Pending single steps run
  /// even when paused. A SimulationError pauses and is shown as `error`.
  void advance(double frameSeconds, bool fixedStep);
  /// Dynamic body under a world point, -1 if none (the top-most shape wins).
  int bodyAt(const Vec2& world) const;
  /// Resizes the viewport, keeping the view centre and scale.
  void resize(int width, int height);
  /// Applies the live cable edits in `cableEdit` to the selected cable; false + `error` if
  /// the engine rejects them.
  bool applyCableEdit();
  /// Overlay for this frame: the controller target, the drag spring and the controller's
  /// drawings (controllerOverlay).
  Overlay overlay() const;
  /// Renderer options for this frame (selection, legend scale, free screen area).
  RenderOptions renderOptions() const;

  World* world() { return world_.get(); }
  const World* world() const { return world_.get(); }

  // Scene and settings (edited by the panels).
  std::string sceneName;  ///< built-in name or file path
  SceneDef scene;         ///< as loaded (reset rebuilds from it)
  bool paused = false;
  int pendingSteps = 0;    ///< single steps requested while paused
  double dt = 1.0 / 60.0;  ///< s
  int substeps = 1;
  Vec2 gravity = Vec2(0, -9.81);  ///< m/s^2
  Camera camera;
  bool showHelp = false;
  std::string error;           ///< last error, shown until dismissed
  std::optional<Vec2> target;  ///< controller target (m), set by clicking empty space
  Gesture gesture;
  std::vector<PanelRect> panels;  ///< this frame's panel rectangles

  // Inspector.
  int selectedCable = 0;
  int selectedBody = -1;
  struct CableEdit {
    double restLength = 0, stiffness = 0, preload = 0, damping = 0;
  } cableEdit;
  /// Tension (N) of every cable over the last `kHistory` steps, ring buffers at `historyHead`.
  static constexpr int kHistory = 600;
  std::vector<std::vector<float>> tensionHistory;
  int historyHead = 0;
  double tensionScale = 1;  ///< legend maximum, grows with the largest tension

  /// The current scene's controller or view (ui/controller_panel.h); rebuilt by open/reset.
  std::unique_ptr<ControllerState> controller;

  // Status.
  double lastFrameSeconds = 0;
  double fps = 0;

 private:
  void afterStep();
  void loadCableEdit();
  std::unique_ptr<World> world_;
  double accumulator_ = 0;
};

}  // namespace cablelab::ui
