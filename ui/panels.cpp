#include "ui/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "ui/controller_panel.h"
#include "ui/input.h"
#include "ui/scene_catalog.h"

namespace cablelab::ui {
namespace {

constexpr ImGuiWindowFlags kFixed =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;

/// A titled separator (ImGui 1.86 has no SeparatorText).
void section(const char* title) {
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextDisabled("%s", title);
}

void record(Sandbox& sandbox) {
  const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  sandbox.panels.push_back({p.x, p.y, s.x, s.y});
}

float menuBar(Sandbox& sandbox, PanelState& state) {
  float height = 0;
  if (ImGui::BeginMainMenuBar()) {
    if (ImGui::BeginMenu("Scene")) {
      for (const SceneEntry& entry : builtinSceneList())
        if (ImGui::MenuItem(entry.name.c_str(), nullptr, entry.name == sandbox.sceneName))
          sandbox.open(entry.name);
      ImGui::Separator();
      if (ImGui::MenuItem("Open file...")) state.showOpen = true;
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
      ImGui::MenuItem("Shortcuts", "h", &sandbox.showHelp);
      ImGui::EndMenu();
    }
    ImGui::TextDisabled("  %s", sandbox.sceneName.c_str());
    height = ImGui::GetWindowSize().y;
    sandbox.panels.push_back({0, 0, static_cast<float>(sandbox.camera.width), height});
    ImGui::EndMainMenuBar();
  }
  return height;
}

void simulationPanel(Sandbox& sandbox, float top) {
  const float height = sandbox.camera.height - top - kStatusHeight;
  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(kLeftWidth, height));
  ImGui::Begin("Simulation", nullptr, kFixed);
  record(sandbox);
  if (ImGui::Button(sandbox.paused ? "Play" : "Pause", ImVec2(80, 0)))
    sandbox.paused = !sandbox.paused;
  ImGui::SameLine();
  if (ImGui::Button("Step", ImVec2(80, 0))) {
    sandbox.paused = true;
    ++sandbox.pendingSteps;
  }
  ImGui::SameLine();
  if (ImGui::Button("Reset", ImVec2(80, 0))) sandbox.reset();
  if (const World* world = sandbox.world())
    ImGui::Text("t = %.3f s   steps %ld", world->time(), world->stepCount());

  section("Integration");
  double dtMs = sandbox.dt * 1000;
  if (ImGui::InputDouble("dt (ms)", &dtMs, 1, 5, "%.3f") && dtMs > 0.01 && dtMs <= 100)
    sandbox.dt = dtMs / 1000;
  if (ImGui::SliderInt("substeps", &sandbox.substeps, 1, 64))
    sandbox.substeps = std::max(1, sandbox.substeps);
  float g[2] = {static_cast<float>(sandbox.gravity.x()), static_cast<float>(sandbox.gravity.y())};
  if (ImGui::DragFloat2("gravity", g, 0.05f, -50, 50, "%.2f")) sandbox.gravity = Vec2(g[0], g[1]);
  if (ImGui::Button("g = 0")) sandbox.gravity = Vec2::Zero();
  ImGui::SameLine();
  if (ImGui::Button("g = -9.81")) sandbox.gravity = Vec2(0, -9.81);

  section("View");
  float zoom = static_cast<float>(1.0 / sandbox.camera.metresPerPixel);
  if (ImGui::DragFloat("px per m", &zoom, 1.0f, 1.0f, 100000.0f, "%.0f") && zoom > 0)
    sandbox.camera.metresPerPixel = 1.0 / zoom;
  if (ImGui::Button("Fit scene view"))
    sandbox.camera = Camera::fit(sandbox.scene.view, sandbox.camera.width, sandbox.camera.height);

  section("Controller");
  drawControllerPanel(sandbox);
  ImGui::End();
}

void cableInspector(Sandbox& sandbox, World& world) {
  if (world.cableCount() == 0) {
    ImGui::TextDisabled("no cables");
    return;
  }
  if (ImGui::BeginListBox("cables", ImVec2(-1, 4.5f * ImGui::GetTextLineHeightWithSpacing()))) {
    for (int i = 0; i < world.cableCount(); ++i) {
      const Cable& c = world.cable(i);
      const std::string label = c.name() + "  " + std::to_string(c.tension()).substr(0, 7) + " N";
      if (ImGui::Selectable(label.c_str(), i == sandbox.selectedCable)) {
        sandbox.selectedCable = i;
        const Cable& s = world.cable(i);
        sandbox.cableEdit = {s.restLength(), s.stiffness(), s.preload(), s.damping()};
      }
    }
    ImGui::EndListBox();
  }
  const int i = std::clamp(sandbox.selectedCable, 0, world.cableCount() - 1);
  const Cable& cable = world.cable(i);
  ImGui::Text("%s: %s", cable.name().c_str(), cable.elastic() ? "elastic" : "rigid");
  ImGui::Text("tension %.4g N %s", cable.tension(), cable.slack() ? "(slack)" : "");
  ImGui::Text("length %.5f m", cable.length());
  bool changed = false;
  auto& e = sandbox.cableEdit;
  ImGui::PushItemWidth(150);
  changed |= ImGui::InputDouble("rest length (m)", &e.restLength, 0.01, 0.1, "%.4f",
                                ImGuiInputTextFlags_EnterReturnsTrue);
  changed |= ImGui::InputDouble("stiffness (N/m)", &e.stiffness, 10, 100, "%.2f",
                                ImGuiInputTextFlags_EnterReturnsTrue);
  changed |= ImGui::InputDouble("preload (m)", &e.preload, 0.001, 0.01, "%.4f",
                                ImGuiInputTextFlags_EnterReturnsTrue);
  changed |= ImGui::InputDouble("damping (N s/m)", &e.damping, 0.1, 1, "%.3f",
                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::PopItemWidth();
  if (changed) sandbox.applyCableEdit();

  if (i < static_cast<int>(sandbox.tensionHistory.size())) {
    const auto& h = sandbox.tensionHistory[i];
    ImGui::PlotLines("##tension", h.data(), static_cast<int>(h.size()), sandbox.historyHead,
                     "tension (N), last 600 steps", 0.0f, static_cast<float>(sandbox.tensionScale),
                     ImVec2(ImGui::GetContentRegionAvail().x, 90));
  }
  ImGui::Text("wrap points (%d)", cable.wraps());
  if (ImGui::BeginTable("path", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                        ImVec2(-1, 8 * ImGui::GetTextLineHeightWithSpacing()))) {
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
        ImGui::Text("pulley %d", p.pulley);
      else
        ImGui::Text("pulley %d v%d", p.pulley, p.vertex);
      ImGui::TableNextColumn();
      ImGui::Text("%.4f", p.world.x());
      ImGui::TableNextColumn();
      ImGui::Text("%.4f", p.world.y());
    }
    ImGui::EndTable();
  }
}

void inspectorPanel(Sandbox& sandbox, float top) {
  const float height = sandbox.camera.height - top - kStatusHeight;
  ImGui::SetNextWindowPos(ImVec2(sandbox.camera.width - kRightWidth, top));
  ImGui::SetNextWindowSize(ImVec2(kRightWidth, height));
  ImGui::Begin("Inspector", nullptr, kFixed);
  record(sandbox);
  if (World* world = sandbox.world()) {
    cableInspector(sandbox, *world);
    const int b = sandbox.selectedBody;
    if (b >= 0 && b < world->bodyCount()) {
      section("Body");
      const BodyState& s = world->body(b);
      ImGui::Text("%s", world->scene().bodies[b].name.c_str());
      ImGui::Text("x %.4f  y %.4f  theta %.4f", s.position.x(), s.position.y(), s.angle);
      ImGui::Text("vx %.3f  vy %.3f  omega %.3f", s.velocity.x(), s.velocity.y(),
                  s.angularVelocity);
    }
    if (!world->warnings().empty()) {
      section("Engine warnings");
      const auto& w = world->warnings();
      for (size_t k = w.size() > 5 ? w.size() - 5 : 0; k < w.size(); ++k)
        ImGui::TextWrapped("%s", w[k].c_str());
    }
  }
  ImGui::End();
}

void statusLine(Sandbox& sandbox) {
  ImGui::SetNextWindowPos(ImVec2(0, sandbox.camera.height - kStatusHeight));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(sandbox.camera.width), kStatusHeight));
  ImGui::Begin("##status", nullptr,
               kFixed | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar |
                   ImGuiWindowFlags_NoSavedSettings);
  record(sandbox);
  if (const World* world = sandbox.world()) {
    const StepStats& s = world->lastStepStats();
    ImGui::Text("%s  t %.3f s   step %.1f us (cables %.1f us)   %.0f fps   wrap points %d   %s",
                sandbox.paused ? "PAUSED" : "running", world->time(), s.stepMicros, s.cableMicros,
                sandbox.fps, s.wrapPoints, "h: help");
  } else {
    ImGui::TextUnformatted("no scene loaded");
  }
  ImGui::End();
}

void helpOverlay(Sandbox& sandbox) {
  if (!sandbox.showHelp) return;
  ImGui::SetNextWindowPos(ImVec2(0.5f * sandbox.camera.width, 0.5f * sandbox.camera.height),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.92f);
  ImGui::Begin("Shortcuts", &sandbox.showHelp,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
  record(sandbox);
  if (ImGui::BeginTable("keys", 2)) {
    for (int k = 0; kShortcuts[k][0]; ++k) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(kShortcuts[k][0]);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(kShortcuts[k][1]);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

void openDialog(Sandbox& sandbox, PanelState& state) {
  if (!state.showOpen) return;
  ImGui::SetNextWindowPos(ImVec2(0.5f * sandbox.camera.width, 120), ImGuiCond_Always,
                          ImVec2(0.5f, 0));
  ImGui::SetNextWindowSize(ImVec2(520, 0));
  ImGui::Begin("Open scene file", &state.showOpen, ImGuiWindowFlags_NoCollapse);
  record(sandbox);
  ImGui::TextUnformatted("Path of a scene JSON file (or a built-in scene name):");
  ImGui::SetNextItemWidth(-1);
  const bool enter = ImGui::InputText("##path", state.openPath.data(), state.openPath.size(),
                                      ImGuiInputTextFlags_EnterReturnsTrue);
  if ((ImGui::Button("Open") || enter) && state.openPath[0] != '\0')
    if (sandbox.open(state.openPath.data())) state.showOpen = false;
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) state.showOpen = false;
  ImGui::End();
}

void errorBanner(Sandbox& sandbox) {
  if (sandbox.error.empty()) return;
  ImGui::SetNextWindowPos(ImVec2(0.5f * sandbox.camera.width, 40), ImGuiCond_Always,
                          ImVec2(0.5f, 0));
  ImGui::SetNextWindowSize(ImVec2(std::min(600.0f, sandbox.camera.width - 40.0f), 0));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(255, 228, 228, 245));
  ImGui::Begin("Error", nullptr, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoResize);
  record(sandbox);
  ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(160, 0, 0, 255));
  ImGui::TextWrapped("%s", sandbox.error.c_str());
  ImGui::PopStyleColor();
  if (ImGui::Button("Dismiss")) sandbox.error.clear();
  ImGui::End();
  ImGui::PopStyleColor();
}

}  // namespace

void drawPanels(Sandbox& sandbox, PanelState& state) {
  sandbox.panels.clear();
  const float top = menuBar(sandbox, state);
  simulationPanel(sandbox, top);
  inspectorPanel(sandbox, top);
  statusLine(sandbox);
  helpOverlay(sandbox);
  openDialog(sandbox, state);
  errorBanner(sandbox);
}

}  // namespace cablelab::ui
