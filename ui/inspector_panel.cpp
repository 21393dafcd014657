// The Inspector panel's contents: cables, the selected body, engine warnings.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "ui/authoring.h"
#include "ui/cable_spans.h"
#include "ui/panel_sections.h"
#include "ui/renderer.h"

namespace cablelab::ui {
namespace {

void cableList(Sandbox& sandbox, const World& world) {
  if (!ImGui::BeginListBox("##cables", ImVec2(-1, 4.5f * ImGui::GetTextLineHeightWithSpacing())))
    return;
  for (int i = 0; i < world.cableCount(); ++i) {
    const Cable& c = world.cable(i);
    char label[160];
    std::snprintf(label, sizeof label, "%s  %.4g N%s", c.name().c_str(), c.tension(),
                  overstretched(c) ? "  OVERSTRETCHED" : "");
    if (ImGui::Selectable(label, i == sandbox.selectedCable)) {
      sandbox.selectedCable = i;
      sandbox.cableEdit = {c.restLength(), c.stiffness(), c.preload(), c.damping()};
    }
  }
  ImGui::EndListBox();
  tooltip("Every cable and its tension; click one (or click it in the view) to inspect it.");
}

void cableEdits(Sandbox& sandbox) {
  auto& e = sandbox.cableEdit;
  struct Field {
    const char* label;
    double* value;
    double step, fastStep;
    const char* format;
    const char* tip;
  };
  const Field fields[] = {
      {"rest length (m)", &e.restLength, 0.01, 0.1, "%.4f",
       "Rest length L; Enter applies it live."},
      {"stiffness (N/m)", &e.stiffness, 10, 100, "%.2f",
       "0: a rigid cable (tension from the constraint); > 0: an elastic band."},
      {"preload (m)", &e.preload, 0.001, 0.01, "%.4f", "Pre-stretch of an elastic cable."},
      {"damping (N s/m)", &e.damping, 0.1, 1, "%.3f",
       "Damping of an elastic cable, times its length rate."},
  };
  bool changed = false;
  ImGui::PushItemWidth(fieldWidth("damping (N s/m)", ImGui::GetFontSize() * 9));
  for (const Field& f : fields) {
    changed |= ImGui::InputDouble(f.label, f.value, f.step, f.fastStep, f.format,
                                  ImGuiInputTextFlags_EnterReturnsTrue);
    tooltip(f.tip);
  }
  ImGui::PopItemWidth();
  if (changed) sandbox.applyCableEdit();
}

void wrapTable(const Cable& cable) {
  ImGui::Text("wrap points (%d)", cable.wraps());
  if (!ImGui::BeginTable("path", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                         ImVec2(-1, 8 * ImGui::GetTextLineHeightWithSpacing())))
    return;
  ImGui::TableSetupColumn("kind");
  ImGui::TableSetupColumn("x (m)");
  ImGui::TableSetupColumn("y (m)");
  ImGui::TableHeadersRow();
  for (const WrapPoint& p : cable.path()) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    if (p.kind == WrapPoint::Kind::Anchor)
      ImGui::TextUnformatted("anchor");
    else if (p.kind == WrapPoint::Kind::Point)
      ImGui::Text("pulley %d", cable.scenePulley(p.pulley));
    else if (p.kind == WrapPoint::Kind::Circle)
      ImGui::Text("circle %d", cable.scenePulley(p.pulley));
    else
      ImGui::Text("pulley %d v%d", cable.scenePulley(p.pulley), p.vertex);
    ImGui::TableNextColumn();
    ImGui::Text("%.4f", p.world.x());
    ImGui::TableNextColumn();
    ImGui::Text("%.4f", p.world.y());
  }
  ImGui::EndTable();
}

/// Per-span tensions of a cable split by gripping wheels, and each wheel's tension ratio.
void spanSection(Sandbox& sandbox, const Cable& cable) {
  SpanTable table = spanTable(cable);
  if (table.spans.empty()) {
    sandbox.shownSpans = {};
    return;
  }
  ImGui::Text("spans (%d)", cable.spanCount());
  tooltip(
      "Each stretch of rope between gripping wheels has its own pull. A rope round a drum holds "
      "while the pull on one side is less than the 'slips at' ratio times the other, and slips "
      "at that ratio: more friction or more rope round the drum holds a bigger ratio. On a "
      "polygon with friction each corner does the same.");
  if (ImGui::BeginTable("spans", 3, ImGuiTableFlags_RowBg)) {
    // The span number narrow, so that the headers with units fit at projector scale (with three
    // equal columns "tension (N)" was cut to "tension (...").
    static const char* const kHeaders[] = {"span", "tension (N)", "length (m)"};
    ImGui::TableSetupColumn(kHeaders[0], ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn(kHeaders[1], ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn(kHeaders[2], ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
    for (int c = 0; c < 3; ++c) {
      ImGui::TableSetColumnIndex(c);
      sandbox.cutHeaders = std::max(sandbox.cutHeaders, ImGui::CalcTextSize(kHeaders[c]).x -
                                                            ImGui::GetContentRegionAvail().x);
      ImGui::TableHeader(kHeaders[c]);
    }
    for (const SpanRow& row : table.spans) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%d", row.span);
      ImGui::TableNextColumn();
      ImGui::Text("%.4g%s", row.tension, row.tension <= 0 ? " slack" : "");
      ImGui::TableNextColumn();
      ImGui::Text("%.4f", row.length);
    }
    ImGui::EndTable();
  }
  for (const WheelRow& w : table.wheels) {
    ImGui::TextWrapped("%s", w.text.c_str());
    for (const CornerRow& c : w.corners) ImGui::TextWrapped("%s", c.text.c_str());
  }
  sandbox.shownSpans = std::move(table);
}

void cableInspector(Sandbox& sandbox, const World& world) {
  if (world.cableCount() == 0) {
    sandbox.shownSpans = {};
    ImGui::TextDisabled("no cables");
    return;
  }
  cableList(sandbox, world);
  const int i = std::clamp(sandbox.selectedCable, 0, world.cableCount() - 1);
  const Cable& cable = world.cable(i);
  ImGui::Text("%s: %s", cable.name().c_str(), cable.elastic() ? "elastic" : "rigid");
  ImGui::Text("tension %.4g N %s", cable.tension(), cable.slack() ? "(slack)" : "");
  // The rest length on a row of its own where the panel is too narrow for both (a 44 m rope
  // at 1280x720 at projector scale).
  char length[64], rest[48];
  std::snprintf(length, sizeof length, "length %.5f m", cable.length());
  std::snprintf(rest, sizeof rest, "(rest %.5f)", cable.restLength());
  ImGui::TextUnformatted(length);
  sameLineIfRoom(ImGui::CalcTextSize(rest).x);
  ImGui::TextUnformatted(rest);
  if (overstretched(cable))
    ImGui::TextColored(ImVec4(0.8f, 0.0f, 0.1f, 1), "overstretched by %.4f m",
                       cable.length() - cable.restLength());
  spanSection(sandbox, cable);
  cableEdits(sandbox);
  pulleyEdits(sandbox, i);
  if (i < static_cast<int>(sandbox.tensionHistory.size())) {
    const auto& h = sandbox.tensionHistory[i];
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "tension 0..%.4g N, last 600 steps",
                  sandbox.tensionScale);
    ImGui::PlotLines("##tension", h.data(), static_cast<int>(h.size()), sandbox.historyHead,
                     overlay, 0.0f, static_cast<float>(sandbox.tensionScale),
                     ImVec2(ImGui::GetContentRegionAvail().x, 5 * ImGui::GetFontSize()));
    tooltip("Tension of the selected cable; the range is the colour bar's (View section).");
  }
  wrapTable(cable);
}

/// Edits of the selected body's definition (an authoring edit: the scene restarts, undo works).
void bodyEdits(Sandbox& sandbox, int b) {
  if (b >= static_cast<int>(sandbox.scene.bodies.size())) return;
  const BodyDef& def = sandbox.scene.bodies[b];
  double mass = def.mass, x = def.position.x(), y = def.position.y();
  double vx = def.velocity.x(), vy = def.velocity.y(), omega = def.angularVelocity;
  ImGui::PushItemWidth(fieldWidth("start x (m)", ImGui::GetFontSize() * 7));
  const bool m =
      ImGui::InputDouble("mass (kg)", &mass, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue);
  tooltip("Edit the body's mass (Enter applies it; the scene restarts; Ctrl+Z undoes it).");
  const bool px =
      ImGui::InputDouble("start x (m)", &x, 0, 0, "%.4f", ImGuiInputTextFlags_EnterReturnsTrue);
  tooltip("The body's starting position, x.");
  const bool py =
      ImGui::InputDouble("start y (m)", &y, 0, 0, "%.4f", ImGuiInputTextFlags_EnterReturnsTrue);
  tooltip("The body's starting position, y.");
  bool v = false;
  if (def.type != BodyType::Static) {
    v |= ImGui::InputDouble("speed x (m/s)", &vx, 0, 0, "%.4g",
                            ImGuiInputTextFlags_EnterReturnsTrue);
    tooltip("Starting speed, x. A driven body keeps its speed whatever pushes on it.");
    v |= ImGui::InputDouble("speed y (m/s)", &vy, 0, 0, "%.4g",
                            ImGuiInputTextFlags_EnterReturnsTrue);
    tooltip("Starting speed, y.");
    v |= ImGui::InputDouble("spin (rad/s)", &omega, 0, 0, "%.4g",
                            ImGuiInputTextFlags_EnterReturnsTrue);
    tooltip("Starting turning speed, anticlockwise.");
  }
  ImGui::PopItemWidth();
  static const char* const types[] = {"moves", "fixed", "driven"};
  static const BodyType kinds[] = {BodyType::Dynamic, BodyType::Static, BodyType::Kinematic};
  int type = static_cast<int>(std::find(kinds, kinds + 3, def.type) - kinds);
  bool t = false;
  for (int k = 0; k < 3; ++k) {
    if (k) sameLineIfRoom(checkboxWidth(types[k]));
    if (ImGui::RadioButton(types[k], type == k)) t = type != k, type = k;
    tooltip(
        "moves: falls and is pulled by cables. fixed: never moves. driven: moves at its set "
        "speed whatever pushes on it.");
  }
  const bool del = ImGui::SmallButton("Delete body");
  tooltip("Remove the body with its cables and joints (Delete key; Ctrl+Z undoes it).");
  if (del) {
    applyEdit(sandbox, withoutBody(sandbox.scene, def.name));
    return;
  }
  if (!(m || px || py || v || t)) return;
  SceneDef next = sandbox.scene;
  BodyDef& edited = next.bodies[b];
  edited.mass = mass;
  edited.position = Vec2(x, y);
  edited.velocity = Vec2(vx, vy);
  edited.angularVelocity = omega;
  edited.type = kinds[type];
  if (applyEdit(sandbox, std::move(next))) sandbox.selectedBody = b;
}

}  // namespace

void inspectorContents(Sandbox& sandbox) {
  World* world = sandbox.world();
  if (!world) return;
  cableInspector(sandbox, *world);
  const int b = sandbox.selectedBody;
  if (b >= 0 && b < world->bodyCount()) {
    section("Body");
    const BodyState& s = world->body(b);
    const BodyDef& def = world->scene().bodies[b];
    ImGui::Text("%s (%s, %.4g kg)", def.name.c_str(),
                def.type == BodyType::Dynamic     ? "dynamic"
                : def.type == BodyType::Kinematic ? "kinematic"
                                                  : "static",
                def.mass);
    ImGui::Text("x %.4f  y %.4f  theta %.4f", s.position.x(), s.position.y(), s.angle);
    ImGui::Text("vx %.3f  vy %.3f  omega %.3f", s.velocity.x(), s.velocity.y(), s.angularVelocity);
    if (sandbox.drag.body == b)
      ImGui::Text("drag %.4g N of %.4g N%s", sandbox.drag.force.norm(), sandbox.dragLimit(b),
                  sandbox.drag.limited ? " (at the limit)" : "");
    bodyEdits(sandbox, b);
  }
  jointEdits(sandbox);
  logSection(sandbox);
}

}  // namespace cablelab::ui
