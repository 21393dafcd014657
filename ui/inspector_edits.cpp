// The Inspector's scene edits: a cable's pulleys (side, grip) and the joints (limits, motor,
// servo). Each change is an authoring edit (ui/authoring.h): the scene restarts, Ctrl+Z undoes it.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ui/authoring.h"
#include "ui/panel_sections.h"

namespace cablelab::ui {
namespace {

bool numberField(const char* label, double* value, const char* format, const char* tip) {
  const bool changed =
      ImGui::InputDouble(label, value, 0, 0, format, ImGuiInputTextFlags_EnterReturnsTrue);
  tooltip(tip);
  return changed;
}

/// A row of radio buttons; true when one was clicked (`*chosen` is then its index).
bool choice(const char* id, const char* const* labels, int n, int* chosen, const char* tip) {
  bool changed = false;
  ImGui::PushID(id);
  for (int k = 0; k < n; ++k) {
    if (k) sameLineIfRoom(checkboxWidth(labels[k]));
    if (ImGui::RadioButton(labels[k], *chosen == k)) changed = *chosen != k, *chosen = k;
    tooltip(tip);
  }
  ImGui::PopID();
  return changed;
}

/// Side and grip of one pulley; true if `p` changed.
bool pulleyRow(PulleyDef& p, int k) {
  ImGui::PushID(k);
  const char* kind = p.kind == PulleyDef::Kind::Point    ? "eyelet"
                     : p.kind == PulleyDef::Kind::Circle ? "round pulley"
                                                         : "polygon pulley";
  ImGui::Text("%d: %s on %s", k, kind, p.body.c_str());
  bool changed = false;
  if (p.kind != PulleyDef::Kind::Point) {
    static const char* const sides[] = {"left", "right", "auto"};
    int side = p.side == WrapSide::Left ? 0 : p.side == WrapSide::Right ? 1 : 2;
    if (choice("side", sides, 3, &side,
               "Which side the cable passes the pulley, walking from the start to the end. "
               "auto: the cable goes round it only where it touches it.")) {
      changed = true;
      p.side = side == 0 ? WrapSide::Left : side == 1 ? WrapSide::Right : WrapSide::Auto;
    }
  }
  if (p.kind == PulleyDef::Kind::Circle) {
    static const char* const grips[] = {"slides", "no slip", "friction"};
    int grip = static_cast<int>(p.grip);
    if (choice("grip", grips, 3, &grip,
               "slides: the rope slides freely. no slip: the rope turns the pulley like a toothed "
               "belt. friction: it holds until one side pulls e^(mu x angle) times harder.")) {
      changed = true;
      p.grip = static_cast<Grip>(grip);
      if (p.grip == Grip::Capstan && p.mu <= 0) p.mu = 0.3;
    }
  }
  if (p.kind == PulleyDef::Kind::Polygon) {
    static const char* const grips[] = {"slides", "friction"};
    int grip = p.grip == Grip::Capstan ? 1 : 0;
    if (choice("grip", grips, 2, &grip,
               "slides: the rope slides freely over the corners. friction: each corner holds "
               "until one side pulls e^(mu x angle) times harder, angle the rope's turn there.")) {
      changed = true;
      p.grip = grip == 1 ? Grip::Capstan : Grip::Frictionless;
      if (p.grip == Grip::Capstan && p.mu <= 0) p.mu = 0.3;
    }
  }
  if (p.grip == Grip::Capstan) {
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 5);
    changed |= numberField("mu", &p.mu, "%.3f", "Friction coefficient between rope and pulley.");
  }
  ImGui::PopID();
  return changed;
}

const char* jointKind(JointDef::Kind k) {
  return k == JointDef::Kind::Revolute    ? "hinge"
         : k == JointDef::Kind::Prismatic ? "slider"
                                          : "weld";
}

/// Limits, motor and servo of one joint; true if `j` changed.
bool jointFields(JointDef& j) {
  bool changed = false;
  const bool slider = j.kind == JointDef::Kind::Prismatic;
  const char* unit = slider ? "m" : "rad";
  char label[64];
  ImGui::PushItemWidth(fieldWidth("max force (N m)", ImGui::GetFontSize() * 7));
  if (slider) {
    double angle = std::atan2(j.axis.y(), j.axis.x()) * 180 / M_PI;
    if (numberField("direction (deg)", &angle, "%.1f",
                    "The line it slides along: 0 = left-right, 90 = up-down.")) {
      j.axis = Vec2(std::cos(angle * M_PI / 180), std::sin(angle * M_PI / 180));
      changed = true;
    }
  }
  changed |= ImGui::Checkbox("limits", &j.enableLimit);
  tooltip(slider ? "Stops the slide between the lowest and the highest position."
                 : "Stops the turn between the lowest and the highest angle.");
  if (j.enableLimit) {
    std::snprintf(label, sizeof label, "lowest (%s)", unit);
    changed |= numberField(label, &j.lower, "%.4g", "Measured from the starting pose.");
    std::snprintf(label, sizeof label, "highest (%s)", unit);
    changed |= numberField(label, &j.upper, "%.4g", "Measured from the starting pose.");
  }
  changed |= ImGui::Checkbox("motor / servo", &j.servo.enabled);
  tooltip(
      "Drives the joint: it pulls towards the target position, which moves at the set "
      "speed (a motor), never harder than the largest force.");
  if (j.servo.enabled) {
    std::snprintf(label, sizeof label, "target (%s)", unit);
    changed |= numberField(label, &j.servo.target, "%.4g", "Where the servo pulls the joint to.");
    std::snprintf(label, sizeof label, "speed (%s/s)", unit);
    changed |= numberField(label, &j.servo.speed, "%.4g",
                           "The target moves at this speed: a motor. 0 holds still.");
    changed |= numberField("stiffness", &j.servo.kp, "%.4g",
                           "How hard it pulls per unit of distance from the target.");
    changed |= numberField("damping", &j.servo.kd, "%.4g", "How hard it resists speed.");
    changed |= numberField(slider ? "max force (N)" : "max force (N m)", &j.servo.maxForce, "%.4g",
                           "The most it ever pushes.");
  }
  ImGui::PopItemWidth();
  return changed;
}

}  // namespace

void pulleyEdits(Sandbox& sandbox, int cable) {
  if (cable < 0 || cable >= static_cast<int>(sandbox.scene.cables.size())) return;
  const CableDef& def = sandbox.scene.cables[cable];
  if (def.pulleys.empty()) return;
  section("Pulleys of this cable");
  for (size_t k = 0; k < def.pulleys.size(); ++k) {
    PulleyDef p = def.pulleys[k];
    if (!pulleyRow(p, static_cast<int>(k))) continue;
    editPulley(sandbox, cable, static_cast<int>(k), p);
    return;
  }
}

void jointEdits(Sandbox& sandbox) {
  if (sandbox.scene.joints.empty()) return;
  section("Joints");
  Authoring& a = *sandbox.authoring;
  const int n = static_cast<int>(sandbox.scene.joints.size());
  a.selectedJoint = std::clamp(a.selectedJoint, 0, n - 1);
  const JointDef& shown = sandbox.scene.joints[a.selectedJoint];
  char preview[160];
  std::snprintf(preview, sizeof preview, "%s (%s)", shown.name.c_str(), jointKind(shown.kind));
  ImGui::SetNextItemWidth(-1);
  if (ImGui::BeginCombo("##joint", preview)) {
    for (int k = 0; k < n; ++k) {
      const JointDef& j = sandbox.scene.joints[k];
      std::snprintf(preview, sizeof preview, "%s (%s: %s - %s)", j.name.c_str(), jointKind(j.kind),
                    j.bodyA.c_str(), j.bodyB.c_str());
      if (ImGui::Selectable(preview, k == a.selectedJoint)) a.selectedJoint = k;
    }
    ImGui::EndCombo();
  }
  tooltip("Pick a joint to edit.");
  ImGui::Text("%s joins %s and %s", jointKind(shown.kind), shown.bodyA.c_str(),
              shown.bodyB.c_str());
  JointDef j = shown;
  if (j.kind == JointDef::Kind::Weld || !jointFields(j)) return;
  SceneDef next = sandbox.scene;
  next.joints[a.selectedJoint] = j;
  applyEdit(sandbox, std::move(next));
}

}  // namespace cablelab::ui
