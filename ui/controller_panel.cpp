#include "ui/controller_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/json_reader.h"
#include "engine/hand/hand_tracking.h"
#include "ui/colormap.h"
#include "ui/hand_plots.h"
#include "ui/panels.h"
#include "ui/time_plot.h"

namespace cablelab::ui {
namespace {

constexpr float kTargetRange = 1.0f;  // m, the target sliders' range about the origin
constexpr Colour kPredictionColour{0.0f, 0.55f, 0.55f, 1.0f};
constexpr Colour kForceColour{0.1f, 0.3f, 0.85f, 1.0f};
constexpr Colour kPlanColour{0.45f, 0.2f, 0.75f, 1.0f};        // purple: not a tension colour
constexpr Colour kAngleColour{0.85f, 0.1f, 0.55f, 1.0f};       // the target's (ui/sandbox.cpp)
constexpr double kAngleArmPixels = 60, kAngleGrabPixels = 12;  // the handle's arm and reach
constexpr float kAngleRange = 0.6f;                            // rad, the angle field's range

constexpr float kSmallestErrorRange = 0.05f, kSmallestXyRange = 0.2f;  // m

// ---------------------------------------------------------------------------------------------
// Hand.

/// The hand's state for `world`, or nullptr when it is not a hand scene.
std::unique_ptr<HandControlState> makeHandState(const World& world) {
  auto h = std::make_unique<HandControlState>();
  const int band = world.findCable(kHandCableNames[0]);
  const int box = world.findBody(kHandBoxName);
  if (band < 0 || box < 0) return nullptr;
  // The controller's model must be the scene's: take the parameters `--set` can change.
  h->model.stiffness = world.cable(band).stiffness();
  h->model.damping = world.cable(band).damping();
  h->model.preload = world.cable(band).preload();
  h->model.boxMass = world.scene().bodies[box].mass;
  h->model.boxDamping = world.scene().bodies[box].linearDamping;
  h->model.turn = !world.scene().bodies[box].fixedRotation;
  const CableDef& membrane = world.cable(band).def();
  if (!membrane.pulleys.empty()) h->model.friction = membrane.pulleys[0].mu;
  h->newGrasp(world);
  if (!h->grasp) return nullptr;  // no hand joints: not the hand
  return h;
}

void handBeforeStep(Sandbox& sandbox, World& world, HandControlState& h) {
  const double t = world.time();
  if (h.rampStart >= 0 && sandbox.target && h.rampLast &&
      (*sandbox.target - *h.rampLast).norm() > 1e-12)
    h.rampStart = -1;      // the user moved the target (a click): the ramp gives way
  if (h.rampStart >= 0) {  // as runTracking's ramp: linear from the start point to the goal
    const double u = std::clamp((t - h.rampStart) / std::max(h.rampSeconds, 1e-9), 0.0, 1.0);
    sandbox.target = h.rampFrom + u * (h.rampTo - h.rampFrom);
    h.rampLast = sandbox.target;
  } else {
    h.rampLast.reset();
  }
  // No target (or the loop switched off): the engine's sequence holds the hand.
  if (h.model.turn) h.grasp->setTargetAngle(h.targetAngle);
  const bool planning = h.law == HandLaw::Mpc && h.enabled && sandbox.target;
  GraspLaw law;
  if (planning)  // as runTracking's MPC law: the box's pose and velocity, the target's pose
    law = [&](const HandJoints& q, const Vec2& at, const HandJoints& commanded) {
      const BodyState& b = world.body(h.box());
      const double angle = h.model.turn ? h.targetAngle : 0.0;
      return h.mpc->update(q, BoxPose(at.x(), at.y(), b.angle), b.velocity,
                           BoxPose(sandbox.target->x(), sandbox.target->y(), angle), commanded);
    };
  h.grasp->beforeStep(world, h.enabled ? sandbox.target : std::nullopt, law);
  const Vec2 box = world.body(h.box()).position;
  if (h.grasp->updates() != h.seenUpdates && !planning) {
    h.seenUpdates = h.grasp->updates();
    h.prediction = h.controller().lastPrediction();
    h.predictionTime = t;
  } else if ((planning || !h.grasp->controlling(t)) &&
             t >= h.predictionTime + h.params.period - 1e-9) {
    // The statics model's view of the current pose, for the overlay.
    h.prediction = h.controller().predict(h.grasp->joints(world), box);
    h.predictionTime = t;
  }
}

void handAfterStep(const Sandbox& sandbox, const World& world, HandControlState& h) {
  h.grasp->afterStep(world);
  const Vec2 box = world.body(h.box()).position;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float error = sandbox.target ? static_cast<float>((box - *sandbox.target).norm()) : nan;
  const float tx = sandbox.target ? static_cast<float>(sandbox.target->x()) : nan;
  const float ty = sandbox.target ? static_cast<float>(sandbox.target->y()) : nan;
  h.history.push(static_cast<float>(world.time()),
                 {static_cast<float>(world.cable(h.grasp->membrane(0)).tension()),
                  static_cast<float>(world.cable(h.grasp->membrane(1)).tension()), error,
                  static_cast<float>(box.x()), static_cast<float>(box.y()), tx, ty});
}

/// The last loss event (what the engine's detection saw), "" if none.
std::string lastLoss(const HandGrasp& g) {
  for (auto e = g.events().rbegin(); e != g.events().rend(); ++e)
    if (e->what.find("unwrapped") != std::string::npos ||
        e->what.find("slack") != std::string::npos)
      return e->what;
  return "";
}

/// One status line: the phase, and when the loop runs or why not.
void graspStatus(const Sandbox& sandbox, const HandControlState& h, double t) {
  const HandGrasp& g = *h.grasp;
  const std::string state = handGraspState(sandbox);
  if (state == "grasp lost") {
    ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(200, 0, 20, 255));
    ImGui::TextWrapped("GRASP LOST (%d): %s%s", g.losses(), lastLoss(g).c_str(),
                       g.phase() == HandGrasp::Phase::Failed ? "; gave up"
                       : g.phase() == HandGrasp::Phase::Lost ? "; stopped"
                                                             : "; re-grasping");
    ImGui::PopStyleColor();
    tooltip(
        "The engine's grasp-loss detection (as `cablelab track`): a membrane unwrapped the box "
        "or went slack after the grasp closed. The hand stops, then grasps again about the box "
        "(at most twice).");
  } else if (g.phase() != HandGrasp::Phase::Control) {
    ImGui::TextWrapped("%s, waiting for both membranes", state.c_str());
  } else if (!g.controlling(t)) {
    ImGui::TextWrapped("%s at %.2f s, control from %.2f s", state.c_str(), g.graspTime(),
                       g.controlStart());
  } else {
    ImGui::TextWrapped("%s; %d updates%s%s", state.c_str(), g.updates(),
                       !h.enabled        ? " (loop off)"
                       : !sandbox.target ? " (no target)"
                                         : "",
                       g.held() ? "" : " (re-grasped)");
  }
}

/// The choice of law on one line, in plain words: react to the error (the Jacobian controller)
/// or plan ahead (MPC), with how far ahead.
void lawChoice(HandControlState& h) {
  int choice = h.law == HandLaw::Mpc ? 1 : 0;
  // As tall as a line of text: the plots below stay in view on a 720-pixel window.
  ImGui::PushStyleVar(ImGuiStyleVar_FramePadding, ImVec2(ImGui::GetStyle().FramePadding.x, 0.0f));
  bool changed = ImGui::RadioButton("react", &choice, 0);
  h.lawRects[0] = lastItemRect();
  tooltip(
      "React to the error: each update moves the fingers to shrink the box's error as it is "
      "now (with PID on, also its sum over time).");
  sameLineIfRoom(checkboxWidth("plan ahead (MPC)"));
  changed |= ImGui::RadioButton("plan ahead (MPC)", &choice, 1);
  h.lawRects[1] = lastItemRect();
  ImGui::PopStyleVar();
  tooltip(
      "Each update plans the fingers' next moves a few steps ahead, keeping the joints in range "
      "and both membranes on the box, and makes the first move (model-predictive control, "
      "`cablelab track --controller mpc`).");
  int horizon = h.horizon;
  if (choice == 1) {
    ImGui::SetNextItemWidth(fieldWidth("steps ahead", ImGui::GetFontSize() * 7));
    changed |= ImGui::SliderInt("steps ahead", &horizon, 1, 20);
    tooltip("How many updates the plan looks ahead (each lasts 0.053 s).");
    ImGui::SameLine();
    ImGui::TextDisabled("%.2f s", horizon * h.params.period);
  }
  if (changed) h.setLaw(choice == 1 ? HandLaw::Mpc : HandLaw::Jacobian, horizon);
}

/// The Jacobian controller's gains and PID toggle; `changed` set when one was edited.
void gainFields(HandControlState& h, bool& changed) {
  sameLineIfRoom(checkboxWidth("PID"));
  changed |= ImGui::Checkbox("PID", &h.pid);
  h.pidRect = lastItemRect();
  tooltip("Add the integral term k_i (the `track --pid` controller).");
  ImGui::PushItemWidth(fieldWidth("k_i (1/s)", ImGui::GetFontSize() * 7));
  changed |= ImGui::InputDouble("k_p", &h.params.kp, 0.01, 0.1, "%.3f");
  tooltip("Proportional gain of the outer loop, per update (dimensionless).");
  changed |= ImGui::InputDouble("k_d", &h.params.kd, 0.01, 0.1, "%.3f");
  tooltip("Derivative gain of the outer loop.");
  if (!h.pid) ImGui::BeginDisabled();
  changed |= ImGui::InputDouble("k_i (1/s)", &h.ki, 0.01, 0.1, "%.3f");
  tooltip("Integral gain (with PID on).");
  if (!h.pid) ImGui::EndDisabled();
  ImGui::PopItemWidth();
  const bool defaults = ImGui::SmallButton("default gains");
  tooltip("Back to the gains the hand starts with: k_p 0.1, k_d 0.58 (k_i 1 with PID).");
  if (defaults) {
    const HandControllerParams d;
    h.params.kp = d.kp, h.params.kd = d.kd, h.ki = kHandPidKi;
    changed = true;
  }
}

void handPanel(Sandbox& sandbox, HandControlState& h) {
  World* world = sandbox.world();
  lawChoice(h);

  // Target: sliders and click-to-set (the overlay cross), or a ramp as `track --ramp`.
  bool hasTarget = sandbox.target.has_value();
  if (ImGui::Checkbox("target", &hasTarget)) {
    sandbox.target = hasTarget ? std::optional<Vec2>(world->body(h.box()).position) : std::nullopt;
    h.rampStart = -1;
  }
  tooltip("A constant target for the box (click empty space in the view to move it).");
  if (sandbox.target) {
    float xy[2] = {static_cast<float>(sandbox.target->x()),
                   static_cast<float>(sandbox.target->y())};
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1);
    if (ImGui::SliderFloat2("##target", xy, -kTargetRange, kTargetRange, "%.3f m")) {
      sandbox.target = Vec2(xy[0], xy[1]);
      h.rampStart = -1;
    }
    tooltip("Target x and y (m).");
    if (h.model.turn) {
      float angle = static_cast<float>(h.targetAngle);
      ImGui::SetNextItemWidth(-ImGui::CalcTextSize("box angle").x -
                              ImGui::GetStyle().ItemSpacing.x);
      if (ImGui::SliderFloat("box angle", &angle, -kAngleRange, kAngleRange, "%.3f rad"))
        h.targetAngle = angle;
      tooltip("The angle to turn the box to (rad), or drag the handle on the target's arm.");
    }
  }
  float ramp[3] = {static_cast<float>(h.rampTo.x()), static_cast<float>(h.rampTo.y()),
                   static_cast<float>(h.rampSeconds)};
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - buttonWidth("Ramp") -
                          ImGui::GetStyle().ItemSpacing.x);
  if (ImGui::DragFloat3("##ramp", ramp, 0.005f, -kTargetRange, kTargetRange, "%.3f")) {
    h.rampTo = Vec2(ramp[0], ramp[1]);
    h.rampSeconds = std::clamp(static_cast<double>(ramp[2]), 0.05, 60.0);
  }
  tooltip("Ramp goal x, y (m) and its duration (s), as `cablelab track --ramp X,Y,SECONDS`.");
  ImGui::SameLine();
  if (ImGui::SmallButton("Ramp")) {
    h.rampFrom = sandbox.target.value_or(world->body(h.box()).position);
    h.rampStart = world->time();
  }
  tooltip("Move the target from where it is to the goal in a straight line over the duration.");
  if (h.rampStart >= 0) ImGui::TextDisabled("ramp from %.2f s", h.rampStart);

  // Gains (the plan has none).
  bool changed = false;
  ImGui::Checkbox("outer loop on", &h.enabled);
  tooltip("Run the outer loop (else the servos hold the last joint targets).");
  if (h.law == HandLaw::Jacobian) gainFields(h, changed);
  if (changed) {
    h.params.kp = std::clamp(h.params.kp, 0.0, 10.0);
    h.params.kd = std::clamp(h.params.kd, 0.0, 10.0);
    h.ki = std::clamp(h.ki, 0.0, 10.0);
    h.applyGains();
  }

  // Grasp sequence.
  ImGui::TextUnformatted("start pose:");
  sameLineIfRoom(buttonWidth("open (grasp)"));
  const bool grasp = ImGui::Button("open (grasp)");
  tooltip(
      "As `cablelab track`: reset, the box at track's default start, swing the fingers open, "
      "close them over 1 s, grasp, then control the box.");
  sameLineIfRoom(buttonWidth("pinch"));
  const bool pinch = ImGui::Button("pinch");
  tooltip("Reset to the pinch pose, the box already between the membranes.");
  if (grasp) {
    startHandGrasp(sandbox);
    return;  // `h` belonged to the old world
  }
  if (pinch) {
    sandbox.reset();
    return;
  }
  graspStatus(sandbox, h, world->time());
  const Vec2 box = world->body(h.box()).position;
  ImGui::Text("box (%.3f, %.3f) m", box.x(), box.y());
  if (sandbox.target) ImGui::Text("error %.4f m", (box - *sandbox.target).norm());
  if (h.prediction.valid)
    ImGui::Text("statics (%.3f, %.3f) m", h.prediction.box.x(), h.prediction.box.y());
  else
    ImGui::TextDisabled("statics: no face-on wrap");

  const float lh = ImGui::GetTextLineHeight();
  const float tensionTop = static_cast<float>(sandbox.tensionScale);
  // The bottom membrane's line dashed over the top one's: in a grasp the two are equal, and a
  // solid line over another hid it (as the exported charts, ui/hand_plots.cpp).
  h.plotLabels.clear();
  timePlot(
      "##tensions", h.history,
      {{"top", 0, IM_COL32(200, 60, 30, 255)}, {"bottom", 1, IM_COL32(40, 90, 200, 255), true}},
      "N tension", 6 * lh, 0, tensionTop, &h.plotLabels);
  tooltip("Membrane tensions; the range is the colour bar's, the bottom membrane's dashed.");
  h.errorRange = fittedRange(h.history, {{"", 2, 0}}, kSmallestErrorRange);
  timePlot("##error", h.history, {{"|box - target|", 2, IM_COL32(170, 20, 120, 255)}}, "m", 5 * lh,
           0, h.errorRange, &h.plotLabels);
  tooltip("Tracking error; the range fits the last 15 s.");
  h.xyRange =
      fittedRange(h.history, {{"", 3, 0}, {"", 4, 0}, {"", 5, 0}, {"", 6, 0}}, kSmallestXyRange);
  // The two targets' dashes half a period apart: where both are 0, both colours show.
  timePlot("##xy", h.history,
           {{"x", 3, IM_COL32(200, 90, 0, 255)},
            {"y", 4, IM_COL32(0, 130, 90, 255)},
            {"x target", 5, IM_COL32(200, 90, 0, 255), true},
            {"y target", 6, IM_COL32(0, 130, 90, 255), true, kDashPeriod / 2}},
           "m", 7 * lh, -h.xyRange, h.xyRange, &h.plotLabels);
  tooltip("Box x and y against time, the targets dashed.");
  if (ImGui::SmallButton("Export CSV")) {
    const std::string name = "cablelab-hand-plots.csv";
    try {
      writeHandHistoryCsv(h, name);
      sandbox.message = "saved " + name;
    } catch (const std::exception& e) {
      sandbox.error = e.what();
    }
  }
  tooltip("The plotted history (last 15 s) as CSV in the working directory.");
  sameLineIfRoom(buttonWidth("Export PNG"));
  if (ImGui::SmallButton("Export PNG")) {
    try {
      const auto paths = exportHandPlots(h, sandbox.tensionScale, "cablelab-hand");
      sandbox.message = "saved " + paths[0] + ", " + paths[1] + " and " + paths[2];
    } catch (const std::exception& e) {
      sandbox.error = e.what();
    }
  }
  h.exportPngButton = {ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y,
                       ImGui::GetItemRectSize().x, ImGui::GetItemRectSize().y};
  tooltip(
      "The three plots for slides: 1920 x 1080 PNGs with axes and legends, in the working "
      "directory.");
}

// ---------------------------------------------------------------------------------------------
// Membrane.

std::unique_ptr<MembraneViewState> makeMembraneState(const World& world) {
  auto m = std::make_unique<MembraneViewState>();
  for (int i = 0; i < world.cableCount(); ++i) {
    const CableDef& def = world.cable(i).def();
    if (def.pulleys.size() != 1 || def.pulleys[0].kind != PulleyDef::Kind::Point) continue;
    if (def.start.body != "world" || def.end.body != "world") continue;
    const int finger = world.findBody(def.pulleys[0].body);
    if (finger < 0) continue;
    m->band = i, m->finger = finger;
    break;
  }
  if (m->band < 0) return nullptr;
  const std::string example = "fit.json";
  std::copy(example.begin(), example.end(), m->path.begin());
  return m;
}

struct MembraneNow {
  MembraneGeometry g;
  MembraneParams params;  ///< the band's k and effective preload
  Vec2 p = Vec2::Zero();  ///< finger point (m)
  Vec2 force = Vec2::Zero();
  bool valid = false;
};

MembraneNow membraneNow(const World& world, const MembraneViewState& m) {
  MembraneNow n;
  const Cable& cable = world.cable(m.band);
  const CableDef& def = cable.def();
  n.g = {def.start.point, def.end.point};
  const BodyState& finger = world.body(m.finger);
  n.p = finger.position + rotate(def.pulleys[0].point, finger.angle);
  // The engine's tension is k (length - L + preload); the model's is k (stretch + preload) with
  // stretch measured from |AB|: the same when the rest length differs from |AB| by this much.
  n.params.k = cable.stiffness();
  n.params.preload = cable.preload() + (n.g.b - n.g.a).norm() - cable.restLength();
  n.valid = cable.stiffness() > 0 && (n.p - n.g.a).norm() > 1e-9 && (n.p - n.g.b).norm() > 1e-9;
  if (n.valid) n.force = membraneForce(n.g, n.params, n.p);
  return n;
}

void membranePanel(Sandbox& sandbox, MembraneViewState& m) {
  World* world = sandbox.world();
  const MembraneNow n = membraneNow(*world, m);
  ImGui::TextWrapped("Membrane model (thesis ch. 3)");
  const Cable& band = world->cable(m.band);
  ImGui::TextWrapped("k %.4g N/m, preload %.4g m", band.stiffness(), band.preload());
  if (n.valid) {
    ImGui::TextWrapped("model F = (%.3f, %.3f) N", n.force.x(), n.force.y());
    ImGui::TextWrapped("model T %.4g N, engine T %.4g N", membraneTension(n.g, n.params, n.p),
                       band.tension());
  }
  ImGui::TextWrapped("fit JSON (cablelab fit output):");
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##fitjson", m.path.data(), m.path.size());
  if (ImGui::Button("Load k, preload"))
    m.messageIsError = !loadFitIntoBand(sandbox, m.path.data(), m.message);
  tooltip("Load the fit's k and preload into the band (its rest length becomes |AB|).");
  if (!m.message.empty()) {
    if (m.messageIsError) {
      ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(204, 26, 26, 255));
      ImGui::TextWrapped("%s", m.message.c_str());
      ImGui::PopStyleColor();
    } else
      ImGui::TextWrapped("%s", m.message.c_str());
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------

namespace {
HandControllerParams gains(const HandControlState& h) {
  HandControllerParams p = h.params;
  p.ki = h.pid ? h.ki : 0.0;
  return p;
}
}  // namespace

void HandControlState::applyGains() {
  if (grasp) grasp->controller().setParams(gains(*this));
}

HandMpcParams HandControlState::mpcParams() const {
  HandMpcParams p;
  p.horizon = horizon;
  p.period = params.period;
  return p;
}

void HandControlState::setLaw(HandLaw newLaw, int newHorizon) {
  if (newLaw == HandLaw::Jacobian && law != newLaw && grasp) grasp->controller().reset();
  law = newLaw;
  horizon = std::clamp(newHorizon, 1, 40);
  mpc = std::make_unique<HandMpc>(model, mpcParams());
}

void HandControlState::newGrasp(const World& world) {
  grasp = std::make_unique<HandGrasp>(model, gains(*this));
  mpc = std::make_unique<HandMpc>(model, mpcParams());
  if (!grasp->attach(world)) grasp.reset();
  prediction = {};
  predictionTime = -1;
  seenUpdates = 0;
}

void writeHandHistoryCsv(const HandControlState& h, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the CSV");
  out << "t,top_tension,bottom_tension,error,x,y,target_x,target_y\n";
  char line[256];
  for (int k = 0; k < h.history.count; ++k) {
    const int i = h.history.slot(k);
    int n = std::snprintf(line, sizeof line, "%.9g", h.history.t[i]);
    for (const auto& series : h.history.values)
      n += std::snprintf(line + n, sizeof line - n, ",%.9g", series[i]);
    out << line << "\n";
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

std::string handGraspState(const Sandbox& sandbox) {
  const HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  if (!h || !h->grasp) return "";
  const HandGrasp& g = *h->grasp;
  switch (g.phase()) {
    case HandGrasp::Phase::Lost:
    case HandGrasp::Phase::Failed:
      return "grasp lost";
    case HandGrasp::Phase::Opening:
    case HandGrasp::Phase::Closing:
      // Re-grasping after a loss still counts as lost until the membranes wrap the box again.
      return !g.held()                                ? "grasp lost"
             : g.phase() == HandGrasp::Phase::Opening ? "opening"
                                                      : "closing";
    case HandGrasp::Phase::Control:
      return h->pinchedStart && g.held() ? "pinch pose" : "grasped";
  }
  return "";
}

bool startHandGrasp(Sandbox& sandbox) {
  sandbox.reset();  // a fresh world; controllerOpened() keeps the gains
  HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  World* world = sandbox.world();
  if (!h || !world) return false;
  if (!sandbox.target) sandbox.target = Vec2::Zero();
  h->newGrasp(*world);
  h->grasp->begin(*world, defaultStart(*sandbox.target));
  h->pinchedStart = false;
  sandbox.paused = false;
  return true;
}

void controllerOpened(Sandbox& sandbox) {
  auto state = std::make_unique<ControllerState>();
  if (const World* world = sandbox.world()) {
    state->hand = makeHandState(*world);
    if (state->hand) {
      HandControlState& h = *state->hand;
      if (sandbox.controller && sandbox.controller->hand) {  // a reset keeps the user's gains
        const HandControlState& old = *sandbox.controller->hand;
        h.params = old.params;
        h.enabled = old.enabled;
        h.pid = old.pid;
        h.ki = old.ki;
        h.setLaw(old.law, old.horizon);
      }
      h.applyGains();
      h.grasp->beginPinched(*world);
      if (!sandbox.target) sandbox.target = world->body(h.box()).position;
    } else {
      state->membrane = makeMembraneState(*world);
      if (state->membrane && sandbox.controller && sandbox.controller->membrane)
        state->membrane->path = sandbox.controller->membrane->path;
    }
  }
  sandbox.controller = std::move(state);
}

const char* controllerSectionTitle(const Sandbox& sandbox) {
  const ControllerState* c = sandbox.controller.get();
  if (sandbox.world() && c && (c->hand || c->membrane)) return "Controller";
  return sandbox.target ? "Marked point" : nullptr;
}

void drawControllerPanel(Sandbox& sandbox) {
  ControllerState* c = sandbox.controller.get();
  if (c && c->hand && sandbox.world()) return handPanel(sandbox, *c->hand);
  if (c && c->membrane && sandbox.world()) return membranePanel(sandbox, *c->membrane);
  if (!sandbox.target) return;
  ImGui::PushTextWrapPos(0);  // a narrow panel at a large UI scale wraps it
  ImGui::Text("(%.3f, %.3f) m", sandbox.target->x(), sandbox.target->y());
  ImGui::PopTextWrapPos();
  if (ImGui::Button("Clear mark")) sandbox.target.reset();
  tooltip("Remove the marked point (Ctrl + click marks another).");
}

void controllerBeforeStep(Sandbox& sandbox, World& world) {
  if (sandbox.controller && sandbox.controller->hand)
    handBeforeStep(sandbox, world, *sandbox.controller->hand);
}

void controllerAfterStep(Sandbox& sandbox, const World& world) {
  if (sandbox.controller && sandbox.controller->hand)
    handAfterStep(sandbox, world, *sandbox.controller->hand);
}

/// The share (0..1) of the arrow from `from` to `to` (m) that stays inside the view (the free
/// area, a margin for the arrowhead and its label in from its edges); 1 when `from` is outside.
namespace {

double arrowShareInView(const Sandbox& sandbox, const Vec2& from, const Vec2& to) {
  const PanelRect f = sandbox.freeArea();
  const double margin = 24 * std::max(1.0, static_cast<double>(sandbox.uiScale));
  const Vec2 a = sandbox.camera.toScreen(from), b = sandbox.camera.toScreen(to);
  const double lo[2] = {f.x + margin, f.y + margin},
               hi[2] = {f.x + f.width - margin, f.y + f.height - margin};
  double share = 1;
  for (int axis = 0; axis < 2; ++axis) {
    if (a[axis] < lo[axis] || a[axis] > hi[axis] || hi[axis] <= lo[axis]) return 1;
    const double d = b[axis] - a[axis];
    if (d > 0 && b[axis] > hi[axis]) share = std::min(share, (hi[axis] - a[axis]) / d);
    if (d < 0 && b[axis] < lo[axis]) share = std::min(share, (lo[axis] - a[axis]) / d);
  }
  return share;
}

}  // namespace

void controllerOverlay(const Sandbox& sandbox, Overlay& overlay) {
  const World* world = sandbox.world();
  if (!world || !sandbox.controller) return;
  if (const HandControlState* h = sandbox.controller->hand.get()) {
    if (const std::optional<Vec2> handle = targetAngleHandle(sandbox)) {
      overlay.arrows.push_back({*sandbox.target, *handle, "", kAngleColour});
      overlay.keys.push_back(
          {Overlay::Key::Marker::Arrow, "target angle (drag its tip to turn it)", kAngleColour});
    }
    if (h->law == HandLaw::Mpc && h->mpc->status().planned) {
      // Where the plan takes the box by the horizon's end.
      const Vec2 box = world->body(h->box()).position;
      overlay.arrows.push_back({box, h->mpc->status().plannedBox.back(), "", kPlanColour});
      overlay.keys.push_back(
          {Overlay::Key::Marker::Arrow, "where the plan takes the box", kPlanColour});
    }
    if (h->prediction.valid) {
      // Its label below it: the target's label sits above the same spot.
      overlay.targets.push_back({h->prediction.box, "statics", kPredictionColour, Vec2(12, 6)});
      overlay.keys.push_back(
          {Overlay::Key::Marker::Cross, "statics model's box", kPredictionColour});
    }
    return;
  }
  if (const MembraneViewState* m = sandbox.controller->membrane.get()) {
    const MembraneNow n = membraneNow(*world, *m);
    if (!n.valid) return;
    // Drawn at a fixed length per newton: the finger's weight (when gravity is on) is a
    // third of the band's width, so the arrow also shows how far the band is from balance.
    const double width = (n.g.b - n.g.a).norm();
    const double weight = world->scene().bodies[m->finger].mass * world->gravity().norm();
    const double reference = weight > 1e-9 ? weight : std::max(n.force.norm(), 1e-9);
    const double metresPerNewton = width / 3 / reference;
    // Pressed far (the "what to try" drag) the arrow ran out of the top of the view: it stops
    // at the view's edge instead, its value written by the tip as always.
    const Vec2 tip = n.p + metresPerNewton * n.force;
    const double fit = arrowShareInView(sandbox, n.p, tip);
    char text[96];
    std::snprintf(text, sizeof text,
                  fit < 1 ? "model F %.3g N (arrow cut to fit)" : "model F %.3g N", n.force.norm());
    overlay.arrows.push_back({n.p, n.p + fit * (tip - n.p), text, kForceColour});
    overlay.keys.push_back({Overlay::Key::Marker::Arrow, "membrane model force", kForceColour});
  }
}

std::optional<Vec2> targetAngleHandle(const Sandbox& sandbox) {
  const HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  if (!h || !h->model.turn || !sandbox.target) return std::nullopt;
  const double arm = kAngleArmPixels * sandbox.camera.metresPerPixel;
  return *sandbox.target + arm * Vec2(std::cos(h->targetAngle), std::sin(h->targetAngle));
}

bool grabsTargetAngleHandle(const Sandbox& sandbox, const Vec2& point) {
  const std::optional<Vec2> handle = targetAngleHandle(sandbox);
  return handle && (*handle - point).norm() <= kAngleGrabPixels * sandbox.camera.metresPerPixel;
}

void dragTargetAngle(Sandbox& sandbox, const Vec2& point) {
  HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  if (!h || !h->model.turn || !sandbox.target) return;
  const Vec2 arm = point - *sandbox.target;
  if (arm.norm() < 1e-12) return;
  h->targetAngle =
      std::clamp(std::atan2(arm.y(), arm.x()), -double(kAngleRange), double(kAngleRange));
}

bool loadFitIntoBand(Sandbox& sandbox, const std::string& path, std::string& message) {
  const MembraneViewState* m = sandbox.controller ? sandbox.controller->membrane.get() : nullptr;
  if (!m || !sandbox.world()) {
    message = "not a membrane scene";
    return false;
  }
  try {
    const MembraneParams fitted = loadFitParameters(path);
    const MembraneNow n = membraneNow(*sandbox.world(), *m);
    // The fit's preload is the straight band's stretch beyond rest: rest length = |AB|.
    sandbox.selectedCable = m->band;
    sandbox.cableEdit = {(n.g.b - n.g.a).norm(), fitted.k, fitted.preload,
                         sandbox.world()->cable(m->band).damping()};
    if (!sandbox.applyCableEdit()) throw std::runtime_error(sandbox.error);
    char text[160];
    std::snprintf(text, sizeof text, "loaded k = %.4g N/m, preload = %.4g m (rest length |AB|)",
                  fitted.k, fitted.preload);
    message = text;
    return true;
  } catch (const std::exception& e) {
    message = e.what();
    return false;
  }
}

MembraneParams loadFitParameters(const std::string& path) {
  const nlohmann::json j = readJsonFile(path);
  JsonReader r(j, path);
  r.allowOtherKeys();  // the rest of `cablelab fit`'s output
  MembraneParams p;
  p.k = r.requiredNumber("k");
  p.preload = r.requiredNumber("preload");
  if (p.k <= 0) r.fail("k", "must be positive (N/m)" + gotValue(p.k));
  if (p.preload < 0) r.fail("preload", "must be >= 0 (m)" + gotValue(p.preload));
  return p;
}

}  // namespace cablelab::ui
