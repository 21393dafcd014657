// Sandbox: the state the interactive app owns (scene, world, camera, selection, controller
// target, settings) and the simulation verbs the panels and the input handler call.
//
// Needs: the engine's public headers and ui/scene_catalog.h; no SDL, no GL. Panels
// (ui/panels.h) and input (ui/input.h) are plain functions over a Sandbox.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/dynamics/world.h"
#include "ui/cable_spans.h"
#include "ui/camera.h"
#include "ui/demo_loop.h"
#include "ui/event_log.h"
#include "ui/overlay.h"
#include "ui/plain_words.h"
#include "ui/renderer.h"

namespace cablelab::ui {

struct ControllerState;  // ui/controller_panel.h
struct Authoring;        // ui/authoring.h
class Timeline;          // ui/timeline.h
class PlotBoard;         // ui/plot_board.h

/// Screen rectangle of a UI panel (px); the scene under it does not take mouse input.
struct PanelRect {
  float x = 0, y = 0, width = 0, height = 0;
  bool contains(const Vec2& p) const {
    return p.x() >= x && p.x() < x + width && p.y() >= y && p.y() < y + height;
  }
};

/// Mouse gesture in progress.
struct Gesture {
  enum class Kind { None, DragBody, Pan, TurnTarget };
  Kind kind = Kind::None;
  Vec2 lastMouse = Vec2::Zero();  ///< px
  Vec2 grabLocal = Vec2::Zero();  ///< DragBody: grabbed point in the body frame (m)
};

/// The mouse drag: a spring-damper force from the grabbed point to the mouse, applied before
/// each step (so the cable solver sees it and a rigid cable resists it), clamped to a number
/// of the body's weights, like the max force of Box2D's mouse joint. While paused a drag poses
/// the body instead (World::poseBody): it follows the mouse as far as its rigid cables and joints
/// let it, the bodies on their other ends following, everything at rest; with `payOut` (Shift
/// held) its rigid cables let out length instead.
struct Drag {
  int body = -1;                  ///< -1: no drag
  Vec2 target = Vec2::Zero();     ///< mouse point (m)
  Vec2 grabLocal = Vec2::Zero();  ///< grabbed point, body frame (m)
  double hz = 5;                  ///< spring frequency (1/s)
  double dampingRatio = 0.7;
  Vec2 force = Vec2::Zero();  ///< last applied force (N)
  bool limited = false;       ///< the last force hit the limit
};

class Sandbox {
 public:
  Sandbox(int width, int height);
  ~Sandbox();

  /// Loads a built-in scene or a scene file. On failure keeps the current scene, stores the
  /// message in `error`, prints it on stderr and returns false.
  bool open(const std::string& nameOrPath);
  /// Reopens the current built-in scene with `parameters` (the Scene panel's sliders); a fitted
  /// view is fitted again to the new run.
  bool rebuild(const std::vector<std::pair<std::string, double>>& parameters);
  /// Replaces the scene by `def` (authoring) keeping the camera; false + `error` if invalid.
  bool replaceScene(const SceneDef& def);
  /// Rebuilds the world from the loaded scene with the current dt, substeps and gravity; the
  /// tension scale goes back to the scene's.
  void reset();
  /// Advances the simulation for one displayed frame: one step of `dt` when `fixedStep`, else
  /// as many steps as `speed` x `frameSeconds` of wall time holds (at most 8). Pending single
  /// steps run even when paused. A SimulationError pauses and is shown as `error`.
  void advance(double frameSeconds, bool fixedStep);
  /// Dynamic body under a world point, -1 if none (the top-most shape wins); with `anyType`
  /// static and kinematic bodies count too.
  int bodyAt(const Vec2& world, bool anyType = false) const;
  /// The cable nearest to a world point within `tolerance` (m), -1 if none.
  int cableAt(const Vec2& world, double tolerance) const;
  /// Resizes the viewport, keeping the view centre and scale.
  void resize(int width, int height);
  /// Applies the live cable edits in `cableEdit` to the selected cable; false + `error` if
  /// the engine rejects them.
  bool applyCableEdit();
  /// Overlay for this frame: the controller target, the drag spring and the controller's
  /// drawings (controllerOverlay), the marker keys and the guard banner.
  Overlay overlay() const;
  /// Renderer options for this frame (selection, legend scale, free screen area).
  RenderOptions renderOptions() const;
  /// The world view's free rectangle (px) between the panels.
  PanelRect freeArea() const;
  /// Fits the camera to the free area: the scene's view, grown to hold every dynamic body,
  /// cable and pulley (so nothing starts cut off), centred in the area between the panels; in
  /// presentation mode, unless a student builds, the scene's parts alone, as large as they fit
  /// (ui/presentation.h).
  void fitView();
  /// The camera centre that puts world point `p` at the free area's centre (current scale).
  Vec2 centreFor(const Vec2& p) const;
  bool fitPending = false;  ///< fit the view once the panels have been laid out
  /// The camera is as the last fit left it (no pan or zoom since): a change of the free area or
  /// the UI scale fits it again (ui/presentation.h).
  bool viewFitted = true;
  /// The fitted view is a close-up that follows the run (a thin, tall demo in presentation
  /// mode, ui/presentation.h).
  bool closeUp = false;
  /// The last fit in presentation mode showed the scene's own view while a student builds
  /// (ui/presentation.h, showsCanvas).
  bool fittedCanvas = false;
  PanelRect fittedArea;       ///< the free area of the last fit
  float fittedScale = 0;      ///< the UI scale of the last fit
  size_t fittedKeyRows = 0;   ///< the marker key's rows drawn before the last fit
  bool presentation = false;  ///< presentation mode: side panels hidden, the scene fitted

  // Drag (see Drag).
  void beginDrag(int body, const Vec2& worldPoint);
  void dragTo(const Vec2& worldPoint, bool payOut = false);
  void endDrag();
  /// The drag force limit (N) for `body`: dragWeights times its weight (at least 9.81 m/s^2).
  double dragLimit(int body) const;
  /// Whether an empty-space click sets the target (a controller uses it).
  bool hasController() const;
  /// A Build tool is chosen (ui/authoring.h): clicks in the view add to the scene.
  bool building() const;

  /// Takes a world the timeline rewound (null: the current one, played forward to the moment);
  /// drops the drag, so that playing on repeats the run (ui/timeline.h).
  void adoptRewound(std::unique_ptr<World> world);

  World* world() { return world_.get(); }
  const World* world() const { return world_.get(); }

  // Scene and settings (edited by the panels).
  /// Built-in name or file path; "edited-" and the scene's name once built or changed in the
  /// window (its built-in sliders no longer apply).
  std::string sceneName;
  /// The file the scene was opened from or last saved to (empty: none since New or a built-in).
  std::string sceneFile;
  /// The scene's name as the window shows it to students: the built-in's name, the file's name,
  /// or the edited scene's own ("my mechanism" for a new one; "hexagon (edited)").
  std::string displayName() const;
  /// displayName() as a file name's stem (no spaces, no extension), for screenshots and plots.
  std::string fileStem() const;
  SceneDef scene;                                          ///< as loaded (reset rebuilds from it)
  std::vector<std::pair<std::string, double>> parameters;  ///< built-in scene's --set values
  bool paused = false;
  int pendingSteps = 0;    ///< single steps requested while paused
  double dt = 1.0 / 60.0;  ///< s
  int substeps = 1;
  double speed = 1;               ///< simulated seconds per wall second (0.1 .. 4)
  Vec2 gravity = Vec2(0, -9.81);  ///< m/s^2
  Camera camera;
  bool follow = false;  ///< the camera keeps the selected body at the view centre
  /// A built-in demo that ends starts again, and its view holds its whole run (ui/demo_loop.h).
  DemoRun demo;
  bool showHelp = false;
  std::string error;           ///< last error, shown until dismissed
  std::string message;         ///< last notice (saved a file, recording), shown in the status
  std::optional<Vec2> target;  ///< controller target (m)
  Gesture gesture;
  Drag drag;
  double dragWeights = 3;         ///< drag force limit in body weights
  std::vector<PanelRect> panels;  ///< this frame's panel rectangles
  RenderOptions draw;             ///< draw toggles (labels, grid, wrap points, ...)

  // Inspector.
  int selectedCable = 0;
  /// A cable clicked in the view (-1: none, or empty space clicked since): in presentation mode,
  /// with no Inspector, the view's notes say its tension (the capstan's and the membrane's "what
  /// to try" ask to watch it).
  int watchedCable = -1;
  int selectedBody = -1;
  struct CableEdit {
    double restLength = 0, stiffness = 0, preload = 0, damping = 0;
  } cableEdit;
  /// Tension (N) of every cable over the last `kHistory` steps, ring buffers at `historyHead`.
  static constexpr int kHistory = 600;
  std::vector<std::vector<float>> tensionHistory;
  int historyHead = 0;
  /// Legend maximum (N): the scene's scale from its loads (ui/tension_scale.h), or the user's
  /// while `tensionScaleLocked` (kept across resets and scenes); never changed by a run.
  double tensionScale = 1;
  double sceneTensionScale = 1;
  bool tensionScaleLocked = false;

  // What the engine says goes to the log (ui/event_log.h); a warning the user's drag or edit
  // caused also shows, in plain words (ui/plain_words.h), as a banner for a few seconds.
  EventLog log;
  std::string banner;
  double bannerUntil = -1;  ///< wall-clock seconds of the sandbox (`clock`)
  double clock = 0;         ///< wall seconds since start (advance() adds frameSeconds)
  UserAction action;        ///< the user's last drag or edit, current until `actionUntil`
  double actionUntil = -1;  ///< `clock` seconds

  // UI scale and projector mode (fonts, line widths); the window applies them between frames.
  float uiScale = 1;
  bool projector = false;

  // Requests for the platform (handled by gui_main between frames).
  bool screenshotRequested = false;
  bool recordToggleRequested = false;
  std::optional<PanelRect> pngRequest;  ///< a window rectangle to save as PNG (plot export)
  std::string pngRequestPath;
  bool recording = false;  ///< set by the platform
  int recordedFrames = 0;  ///< set by the platform
  double recordFps = 0;    ///< clip frames per simulated second; 0: the format's (defaultClipFps)

  /// The current scene's controller or view (ui/controller_panel.h); rebuilt by open/reset.
  std::unique_ptr<ControllerState> controller;
  /// The scene editor (ui/authoring.h): tool, sizes, undo and redo; open() clears its history.
  std::unique_ptr<Authoring> authoring;
  /// The last 30 s, for rewinding (ui/timeline.h); cleared by open() and reset().
  std::unique_ptr<Timeline> timeline;
  /// The Plots section's charts (ui/plot_board.h); open() clears them, reset() their samples.
  std::unique_ptr<PlotBoard> plots;

  // What the Scene panel showed last (for the scripted checks).
  std::string shownTitle, shownDescription;
  /// The selected cable's span table as the Inspector showed it (empty: one span).
  SpanTable shownSpans;

  /// How far (px) the widest row of the Simulation and the Inspector panel (or a header of the
  /// Inspector's tables) reached past the panel's width or its column in the last frame each
  /// was open (0: every row fits).
  std::array<float, 2> panelOverflow{};
  /// The status line's text in the last frame.
  std::string shownStatus;
  /// The scene's name as the menu strip showed it in the last frame ("": no room for it).
  std::string shownStripName;
  /// How far (px) the menu strip's items reached past the window's width in the last frame.
  float stripOverflow = 0;
  /// How far (px) the status line's text reached past the window's width in the last frame.
  float statusOverflow = 0;
  /// Buttons of the Run row drawn narrower than their text in the last frame (0: none).
  int truncatedButtons = 0;
  /// The Error box's window in the last frame it was shown (px).
  PanelRect errorBox;
  /// The speed slider of the Run section and its value's text in the last frame (px).
  PanelRect speedSlider, speedValue;
  /// Presentation mode's Record (Stop while recording) button in the last frame (px).
  PanelRect recordButton;
  /// A cable was clicked in the view: the next frame opens the Inspector if it is collapsed.
  bool showInspector = false;
  /// How far (px) the widest table header of the Inspector reached past its column (counted
  /// in panelOverflow[1]).
  float cutHeaders = 0;
  /// Whether the Inspector was open (not collapsed, not hidden) in the last frame.
  bool inspectorOpen = false;
  /// Whether the Simulation panel's Plots and Build sections were open in the last frame.
  bool plotsSectionOpen = false, buildSectionOpen = false;
  /// The title of the Simulation panel's controller section in the last frame ("": none).
  std::string controllerSection;

  /// Where the last frame's labels, bars, key, banner and scene went (px), for the scripts.
  DrawnView drawn;

  // Status.
  double lastFrameSeconds = 0;
  double fps = 0;

 private:
  bool adopt(SceneDef def, const std::string& name, bool fitCamera);
  void afterStep();
  void restartDemo();
  void applyDrag();
  void sayPose(const PoseResult& pose);
  void settleBeforeRunning();
  void checkWarnings();
  void loadCableEdit();
  std::unique_ptr<World> world_;
  double accumulator_ = 0;
  bool wasPaused_ = false;      ///< paused at the last advance(): the next steps resume the world
  size_t inputsAfterStep_ = 0;  ///< the world's history length after its last step: more is an
                                ///< edit while paused (settleBeforeRunning)
};

}  // namespace cablelab::ui
