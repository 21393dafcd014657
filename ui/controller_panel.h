// Controller hook: the per-scene controllers and views of the sandbox, kept in one file pair so
// they can be wired in without touching the rest of the sandbox.
//
//   hand      the statics-based Jacobian controller of thesis section 4.3
//             (engine/hand/hand_controller.h) runs live: the target is `sandbox.target` (click
//             empty space, or the sliders), gains k_p, k_d, k_i and the PID toggle are editable,
//             the grasp sequence (open pose -> closing ramp -> grasp -> control, as `cablelab
//             track`) can be started and reset; membrane tensions and tracking error are plotted
//             against time; the overlay shows the target and the statics model's box prediction.
//   membrane  the chapter 3 model force F = -T (u1 + u2) (engine/membrane/membrane_model.h) is
//   drawn at
//             the finger point, and k and preload fitted by `cablelab fit` (its JSON output) can
//             be loaded into the band.
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
#include "engine/hand/hand_model.h"
#include "engine/membrane/membrane_model.h"
#include "ui/overlay.h"
#include "ui/sandbox.h"

namespace cablelab::ui {

/// Fixed-length history of samples against time (oldest overwritten), for the live plots.
struct TimeHistory {
  static constexpr int kLength = 900;      ///< samples (15 s at the default 60 Hz)
  std::vector<float> t;                    ///< s
  std::vector<std::vector<float>> values;  ///< one ring per series, NaN = no value
  int head = 0, count = 0;
  explicit TimeHistory(int series = 0);
  void push(float time, const std::vector<float>& sample);
  void clear();
};

/// Live state of the hand controller (per world; gains survive a reset).
struct HandControlState {
  enum class Phase { Pinched, Closing, Grasped };
  HandModel model;  ///< from the scene's membranes and box
  HandControllerParams params;
  bool enabled = true;     ///< the outer loop runs (once grasped and settled)
  bool pid = false;        ///< use params.ki (else k_i = 0)
  double ki = kHandPidKi;  ///< the integral gain used when `pid` (per update, 1/s)
  std::unique_ptr<HandController> controller;
  Phase phase = Phase::Pinched;
  double sequenceStart = 0;  ///< s, world time the grasp sequence began
  double closeTime = 1.0;    ///< s, open pose -> pinch pose ramp
  double graspTime = -1;     ///< s, both membranes wrap the box; -1 not yet
  /// Grasp loss: after the grasp, a membrane stopped wrapping the box (or went slack) for
  /// longer than kGraspLossSeconds; the world time it happened, -1 while held.
  double lostTime = -1;
  double offSince = -1;  ///< s, when a membrane last let go of the box; -1 both hold it
  std::string lostWhy;
  double controlStart = 0;  ///< s, the outer loop starts here
  double nextUpdate = 0;    ///< s, next outer-loop tick
  int updates = 0;
  HandJoints open = HandJoints::Zero();
  HandJoints offset = HandJoints::Zero();  ///< controller's accumulated joint-target change
  HandJoints commanded = HandJoints::Zero();
  std::array<int, 6> joints{};  ///< world joint index of each HandJoints entry
  int box = -1;
  std::array<int, 2> cables{-1, -1};
  BoxPrediction prediction;    ///< the statics model at the last outer tick
  double predictionTime = -1;  ///< s
  /// top tension, bottom tension (N), |box - target|, box x, box y, target x, target y (m)
  TimeHistory history{7};
  float errorRange = 0.05f, xyRange = 0.2f;  ///< stable plot ranges (m), grow only
  // A ramp target as `cablelab track --ramp X,Y,SECONDS`: from the box to `rampTo` over
  // `rampSeconds`, starting at world time `rampStart` (-1: a constant target).
  double rampStart = -1, rampSeconds = 2;
  Vec2 rampFrom = Vec2::Zero(), rampTo = Vec2(0.1, 0.1);
  std::optional<Vec2> rampLast;  ///< the target the ramp set last (a different one: a click)
  PanelRect plotRect;            ///< screen rectangle of the plots (for the PNG export)
  double lastSample = -1;        ///< s

  void rebuildController();
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

/// A membrane must be off the box this long (s) before the grasp counts as lost.
inline constexpr double kGraspLossSeconds = 0.1;

/// The hand's grasp state as the panel shows it: "pinch pose", "closing", "grasped",
/// "grasp lost"; "" when the scene is not the hand.
std::string handGraspState(const Sandbox& sandbox);

/// Sets up the state for the sandbox's current world (after open() or reset()).
void controllerOpened(Sandbox& sandbox);

/// The hand's grasp sequence, as `cablelab track` runs it: resets the world, swings the fingers
/// to the open pose and ramps them closed; once both membranes wrap the box (and the squeeze
/// has settled) the outer loop drives the box to `sandbox.target` (set to (0, 0) if unset).
/// False if the current scene is not the hand.
bool startHandGrasp(Sandbox& sandbox);

/// ImGui widgets for the current scene's controller; called inside an open window.
void drawControllerPanel(Sandbox& sandbox);

/// Applies the controller to `world` before a step (servo targets, forces).
void controllerBeforeStep(Sandbox& sandbox, World& world);

/// Records the plots' samples after a step.
void controllerAfterStep(Sandbox& sandbox, const World& world);

/// Adds the controller's drawings (statics prediction, model force) to `overlay`.
void controllerOverlay(const Sandbox& sandbox, Overlay& overlay);

/// Loads `cablelab fit` output into the membrane scene's band (World::setCableParameters): k,
/// preload, rest length |AB|; `message` says what happened. False on any error (bad file, not
/// a membrane scene), the band unchanged.
bool loadFitIntoBand(Sandbox& sandbox, const std::string& path, std::string& message);

/// Reads k and preload from a `cablelab fit` JSON output file; throws InputError naming the
/// file and field.
MembraneParams loadFitParameters(const std::string& path);

}  // namespace cablelab::ui
