// Controller hook: the per-scene controllers and views of the sandbox, kept in one file pair so
// they can be wired in without touching the rest of the sandbox.
//
//   hand      the statics-based Jacobian controller of thesis section 4.3
//             (engine/hand/hand_controller.h) or model-predictive control
//             (engine/hand/hand_mpc.h, "plan ahead", with its horizon) runs live: the target is
//             `sandbox.target` (click empty space, or the sliders), gains k_p, k_d, k_i and the
//             PID toggle are editable,
//             the grasp sequence and the grasp-loss detection are the engine's
//             (engine/hand/hand_grasp.h, the code `cablelab track` runs) and can be started and
//             reset; membrane tensions and tracking error are plotted against time; the overlay
//             shows the target and the statics model's box prediction.
//   membrane  the chapter 3 model force F = -T (u1 + u2) (engine/membrane/membrane_model.h) is
//             drawn at the finger point, and k and preload fitted by `cablelab fit` (its JSON
//             output) can be loaded into the band.
//
// Needs: ui/sandbox.h and Dear ImGui (a frame in progress for the panel). The sandbox calls
// controllerOpened() after every open() and reset(), controllerBeforeStep() before and
// controllerAfterStep() after every World::step(), controllerOverlay() from overlay(), and
// drawControllerPanel() inside its Simulation window every frame.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "engine/hand/hand_controller.h"
#include "engine/hand/hand_grasp.h"
#include "engine/hand/hand_model.h"
#include "engine/hand/hand_mpc.h"
#include "engine/hand/hand_tracking.h"
#include "engine/membrane/membrane_model.h"
#include "ui/overlay.h"
#include "ui/sandbox.h"
#include "ui/time_plot.h"

namespace cablelab::ui {

/// Live state of the hand controller (per world; gains survive a reset). The grasp sequence,
/// the outer loop and the grasp-loss detection are the engine's (engine/hand/hand_grasp.h, the
/// same code `cablelab track` runs); the panel adds targets, plots and the overlay.
struct HandControlState {
  HandModel model;  ///< from the scene's membranes and box
  HandControllerParams params;
  bool enabled = true;     ///< the outer loop runs (once grasped and settled)
  bool pid = false;        ///< use params.ki (else k_i = 0)
  double ki = kHandPidKi;  ///< the integral gain used when `pid` (per update, 1/s)
  /// The outer loop's law: the Jacobian controller ("react to the error") or MPC ("plan
  /// ahead", `cablelab track --controller mpc --horizon N`).
  HandLaw law = HandLaw::Jacobian;
  int horizon = HandMpcParams{}.horizon;  ///< MPC: updates planned ahead
  std::unique_ptr<HandGrasp> grasp;
  std::unique_ptr<HandMpc> mpc;  ///< the MPC's plan and models (used when `law` is Mpc)
  /// Screen rectangles of the two law choices and the PID toggle, as last drawn (px): where a
  /// scripted click picks them (ui/law_target_scenario.h).
  PanelRect lawRects[2], pidRect;
  bool pinchedStart = true;    ///< the scene as built (pinched), not a grasp sequence
  BoxPrediction prediction;    ///< the statics model at the last outer tick
  double predictionTime = -1;  ///< s
  int seenUpdates = 0;         ///< grasp->updates() when `prediction` was taken
  /// top tension, bottom tension (N), |box - target|, box x, box y, target x, target y (m)
  TimeHistory history{7};
  float errorRange = 0.05f, xyRange = 0.2f;  ///< plot ranges (m), fitted to the last 15 s
  // A ramp target as `cablelab track --ramp X,Y,SECONDS`: from the box to `rampTo` over
  // `rampSeconds`, starting at world time `rampStart` (-1: a constant target).
  double rampStart = -1, rampSeconds = 2;
  Vec2 rampFrom = Vec2::Zero(), rampTo = Vec2(0.1, 0.1);
  std::optional<Vec2> rampLast;  ///< the target the ramp set last (a different one: a click)
  PanelRect exportPngButton;     ///< screen rectangle of the plots' "Export PNG" (px)
  /// Screen rectangles of the plots' legend texts, as last drawn (px): no two may overlap.
  std::vector<PanelRect> plotLabels;
  /// The box's target angle (rad) when it may turn (model.turn, the scene's turn=1): the field
  /// in the panel, or the handle on the target marker's arm in the view.
  double targetAngle = 0;

  /// The engine's controller (gains from `params`, `pid` and `ki`).
  const HandController& controller() const { return grasp->controller(); }
  int box() const { return grasp->boxBody(); }
  /// Applies the edited gains to the running controller.
  void applyGains();
  /// A fresh grasp sequence for `world` (gains applied), and a fresh MPC.
  void newGrasp(const World& world);
  /// Switches the outer loop's law (or the MPC's horizon) from the next update on; the law
  /// taking over starts afresh from the current joints and box.
  void setLaw(HandLaw newLaw, int newHorizon);
  /// The MPC's parameters: the default weights, `horizon`, the Jacobian controller's period.
  HandMpcParams mpcParams() const;
};

/// The membrane scene's view: model force and fitted parameters.
struct MembraneViewState {
  int band = -1, finger = -1;
  std::array<char, 512> path{};  ///< the fit JSON file to load
  std::string message;           ///< result of the last load
  bool messageIsError = false;
};

struct ControllerState {
  std::unique_ptr<HandControlState> hand;
  std::unique_ptr<MembraneViewState> membrane;
};

/// Writes the hand's plot history as CSV (t, both tensions, error, x, y, target x, target y);
/// throws std::runtime_error naming the path.
void writeHandHistoryCsv(const HandControlState& h, const std::string& path);

/// The hand's grasp state as the panel shows it, from the engine's sequence and loss detection:
/// "pinch pose" (the scene as built, held), "opening", "closing", "grasped", "grasp lost" (lost
/// and not grasped again yet); "" when the scene is not the hand.
std::string handGraspState(const Sandbox& sandbox);

/// Sets up the state for the sandbox's current world (after open() or reset()).
void controllerOpened(Sandbox& sandbox);

/// The hand's grasp sequence, the one `cablelab track` runs (HandGrasp::begin): resets the world,
/// places the box at `cablelab track`'s default start for the target (defaultStart), swings the
/// fingers to the open pose about it and ramps them closed; once both membranes wrap the box
/// (and the squeeze has settled) the outer loop drives the box to `sandbox.target` (set to
/// (0, 0) if unset). False if the current scene is not the hand.
bool startHandGrasp(Sandbox& sandbox);

/// The Simulation panel's section for the controller: "Controller" when the scene has one (the
/// hand, the membrane), "Marked point" when it has none but a point is marked (Ctrl + click),
/// null otherwise (no section: a line saying there is no controller told a student nothing).
const char* controllerSectionTitle(const Sandbox& sandbox);

/// ImGui widgets for the current scene's controller, or the marked point; called inside an open
/// window.
void drawControllerPanel(Sandbox& sandbox);

/// Applies the controller to `world` before a step (servo targets, forces).
void controllerBeforeStep(Sandbox& sandbox, World& world);

/// Records the plots' samples after a step.
void controllerAfterStep(Sandbox& sandbox, const World& world);

/// Adds the controller's drawings (statics prediction, model force) to `overlay`.
void controllerOverlay(const Sandbox& sandbox, Overlay& overlay);

/// The handle at the end of the target marker's arm (m), which turns the box's target angle:
/// shown on the hand with a box that may turn, and a target.
std::optional<Vec2> targetAngleHandle(const Sandbox& sandbox);
/// Whether a press at `point` (m) grabs that handle.
bool grabsTargetAngleHandle(const Sandbox& sandbox, const Vec2& point);
/// Points the target angle from the target towards `point` (m) (the handle dragged there).
void dragTargetAngle(Sandbox& sandbox, const Vec2& point);

/// Loads `cablelab fit` output into the membrane scene's band (World::setCableParameters): k,
/// preload, rest length |AB|; `message` says what happened. False on any error (bad file, not
/// a membrane scene), the band unchanged.
bool loadFitIntoBand(Sandbox& sandbox, const std::string& path, std::string& message);

/// Reads k and preload from a `cablelab fit` JSON output file; throws InputError naming the
/// file and field.
MembraneParams loadFitParameters(const std::string& path);

}  // namespace cablelab::ui
