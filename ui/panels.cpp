#include "ui/panels.h"

#include <imgui.h>
#include <imgui_internal.h>  // the window's widest row (ImGuiWindow::DC.CursorMaxPos)

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "ui/authoring.h"
#include "ui/controller_panel.h"
#include "ui/input.h"
#include "ui/panel_sections.h"
#include "ui/plain_words.h"
#include "ui/plot_board.h"
#include "ui/plot_panel.h"
#include "ui/presentation.h"
#include "ui/scene_catalog.h"
#include "ui/scene_guide.h"
#include "ui/timeline_panel.h"

namespace cablelab::ui {
namespace {

// The side panels and the status line draw no background of their own: the window clears the
// whole frame in the panels' colour and the world only inside the free area (gui_main.cpp). On
// Xvfb's software GL the panels' background quads (textured and blended, half the window) cost
// more than everything else in a frame.
constexpr ImGuiWindowFlags kPanelBackground = ImGuiWindowFlags_NoBackground;

void record(Sandbox& sandbox) {
  const ImVec2 p = ImGui::GetWindowPos(), s = ImGui::GetWindowSize();
  sandbox.panels.push_back({p.x, p.y, s.x, s.y});
}

void copyPath(std::array<char, 512>& field, const std::string& text) {
  field.fill('\0');
  std::copy_n(text.begin(), std::min(text.size(), field.size() - 1), field.begin());
}

void sceneMenu(Sandbox& sandbox, PanelState& state) {
  if (!ImGui::BeginMenu("Scene")) return;
  for (const SceneEntry& entry : builtinSceneList()) {
    if (ImGui::MenuItem(entry.name.c_str(), nullptr, entry.name == sandbox.sceneName))
      sandbox.open(entry.name);
    tooltip(sceneMenuTip(entry.name, entry.description).c_str());
  }
  ImGui::Separator();
  if (ImGui::BeginMenu("Bundled scene files")) {
    const auto files = bundledSceneFiles();
    if (files.empty()) ImGui::TextDisabled("assets/scenes not found");
    for (const std::string& f : files) {
      const std::string name = std::filesystem::path(f).filename().string();
      if (ImGui::MenuItem(name.c_str(), nullptr, f == sandbox.sceneName)) sandbox.open(f);
      tooltip(f.c_str());
    }
    ImGui::EndMenu();
  }
  if (ImGui::MenuItem("Open file...")) state.showOpen = true;
  tooltip("Open a scene JSON file by path (or drop the file on the window).");
  if (ImGui::MenuItem("Save scene as...")) {
    state.showSave = true;
    if (state.savePath[0] == '\0')
      copyPath(state.savePath,
               (sandbox.scene.name.empty() ? "scene" : sandbox.scene.name) + std::string(".json"));
  }
  tooltip("Write the current scene (as edited) as scene JSON that `cablelab run` loads.");
  ImGui::EndMenu();
}

void viewMenu(Sandbox& sandbox, PanelState& state) {
  if (!ImGui::BeginMenu("View")) return;
  ImGui::MenuItem("labels", nullptr, &sandbox.draw.labels);
  ImGui::MenuItem("grid", nullptr, &sandbox.draw.grid);
  ImGui::MenuItem("wrap points", nullptr, &sandbox.draw.wrapPoints);
  ImGui::MenuItem("tensions", nullptr, &sandbox.draw.tensions);
  ImGui::MenuItem("forces", nullptr, &sandbox.draw.forces);
  ImGui::MenuItem("marker key", nullptr, &sandbox.draw.markerLegend);
  ImGui::Separator();
  if (ImGui::MenuItem("projector mode", nullptr, &sandbox.projector))
    sandbox.uiScale = sandbox.projector ? 2 : 1;
  tooltip("Large fonts and thick lines for a lecture hall.");
  if (ImGui::MenuItem("presentation mode", "p", sandbox.presentation)) togglePresentation(sandbox);
  tooltip("Hide the side panels and fit the scene to the window (p again brings them back).");
  if (ImGui::MenuItem("fit scene view", "v")) sandbox.fitView();
  tooltip("Fit the scene to the view; it stays fitted until you pan or zoom.");
  if (ImGui::MenuItem("collapse both panels")) state.collapseLeft = state.collapseRight = true;
  ImGui::EndMenu();
}

/// Presentation mode's controls in the menu bar: the side panels are hidden.
void presentationControls(Sandbox& sandbox) {
  ImGui::TextDisabled("|");
  if (ImGui::Button(sandbox.paused ? "Play" : "Pause")) sandbox.paused = !sandbox.paused;
  tooltip("Run or pause the simulation (space).");
  if (ImGui::Button("Step")) {
    sandbox.paused = true;
    ++sandbox.pendingSteps;
  }
  tooltip("Pause and advance one time step (s).");
  if (ImGui::Button("Reset")) sandbox.reset();
  tooltip("Start the scene again (r).");
  // F9's clip, for a presenter at the projector without the keyboard's help list. Red while
  // it records; the status line says where the clip went.
  const bool recording = sandbox.recording;
  if (recording) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.25f, 0.2f, 1));
  if (ImGui::Button(recording ? "Stop###record" : "Record###record"))
    sandbox.recordToggleRequested = true;
  if (recording) ImGui::PopStyleColor();
  sandbox.recordButton = lastItemRect();
  tooltip(recording ? "Stop recording and save the clip (F9)."
                    : "Record a clip of the view into the working folder (F9).");
  if (ImGui::Button("Panels")) togglePresentation(sandbox);
  tooltip("Leave presentation mode: show the side panels again (p).");
}

float menuBar(Sandbox& sandbox, PanelState& state) {
  float height = 0;
  if (ImGui::BeginMainMenuBar()) {
    sceneMenu(sandbox, state);
    buildMenu(sandbox);
    viewMenu(sandbox, state);
    if (ImGui::BeginMenu("Help")) {
      ImGui::MenuItem("Shortcuts", "h", &sandbox.showHelp);
      ImGui::EndMenu();
    }
    if (sandbox.presentation) presentationControls(sandbox);
    // The scene's name where it fits whole (a small window at projector scale has no room).
    const std::string name = "  " + sandbox.displayName();
    const float right = static_cast<float>(sandbox.camera.width) - ImGui::GetStyle().ItemSpacing.x;
    sandbox.shownStripName.clear();
    if (ImGui::GetCursorScreenPos().x + ImGui::CalcTextSize(name.c_str()).x <= right) {
      ImGui::TextDisabled("%s", name.c_str());
      sandbox.shownStripName = sandbox.displayName();
    }
    sandbox.stripOverflow = std::max(0.0f, ImGui::GetItemRectMax().x - right);
    height = ImGui::GetWindowSize().y;
    sandbox.panels.push_back({0, 0, static_cast<float>(sandbox.camera.width), height});
    ImGui::EndMainMenuBar();
  }
  return height;
}

/// Default widths for the window size and UI scale; on a narrow window the Inspector starts
/// collapsed and the Simulation panel takes at most a third of the width.
void layoutFor(Sandbox& sandbox, PanelState& state) {
  if (state.layoutScale == sandbox.uiScale) return;
  const float s = sandbox.uiScale, w = static_cast<float>(sandbox.camera.width);
  state.leftWidth = std::min(kLeftWidth * s, std::max(0.34f * w, 200.0f));
  state.rightWidth = std::min(kRightWidth * s, 0.4f * w);
  if (state.layoutScale == 0 && w < kNarrowWindow * s) state.collapseRight = true;
  state.layoutScale = s;
}

/// A side panel pinned to the left or right edge: its height fills the space between the menu
/// and the status line, the user resizes its width and collapses it.
bool beginSidePanel(Sandbox& sandbox, PanelState& state, const char* name, bool left, float top) {
  const float w = static_cast<float>(sandbox.camera.width);
  const float height = sandbox.camera.height - top - kStatusHeight * sandbox.uiScale;
  float& width = left ? state.leftWidth : state.rightWidth;
  width = std::clamp(width, 160.0f, std::max(160.0f, 0.6f * w));
  ImGui::SetNextWindowPos(ImVec2(left ? 0 : w - width, top), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(width, height), ImGuiCond_Always);
  bool& collapse = left ? state.collapseLeft : state.collapseRight;
  if (collapse) ImGui::SetNextWindowCollapsed(true, ImGuiCond_Always);
  collapse = false;
  // Rows fit the width (ui/panels.h; no horizontal scrolling: with it ImGui widens the work
  // area to the widest row, and rows sized to the work area then keep the scrollbar). No
  // background: the window clears the panels' area in their colour (gui_main.cpp).
  const bool open = ImGui::Begin(name, nullptr, ImGuiWindowFlags_NoMove | kPanelBackground);
  record(sandbox);
  // The user's resize shows up as this frame's size: keep it for the next frame.
  if (open) width = ImGui::GetWindowSize().x;
  return open;
}

/// How far (px) the current window's widest row reaches past its content area; 0 if none.
float rowOverflow() {
  const ImGuiWindow* w = ImGui::GetCurrentWindow();
  return std::max(0.0f, w->DC.CursorMaxPos.x - w->WorkRect.Max.x);
}

void simulationPanel(Sandbox& sandbox, PanelState& state, float top) {
  if (beginSidePanel(sandbox, state, "Simulation", true, top)) {
    runPanel(sandbox);
    timelinePanel(sandbox);
    if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) scenePanel(sandbox);
    const char* controller = controllerSectionTitle(sandbox);
    sandbox.controllerSection = controller ? controller : "";
    if (controller && ImGui::CollapsingHeader(controller, ImGuiTreeNodeFlags_DefaultOpen))
      drawControllerPanel(sandbox);
    if (!sandbox.plots->charts.empty()) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    sandbox.plotsSectionOpen = ImGui::CollapsingHeader("Plots");
    if (sandbox.plotsSectionOpen) plotsPanel(sandbox);
    tooltip("Any quantity against time, several at once; export for slides (PNG and CSV).");
    // Open while a tool is chosen (a script or a shortcut can choose one with the section shut).
    if (sandbox.authoring->tool != Authoring::Tool::None) ImGui::SetNextItemOpen(true);
    sandbox.buildSectionOpen = ImGui::CollapsingHeader("Build");
    if (sandbox.buildSectionOpen) authoringPanel(sandbox);
    tooltip("Add bodies, pulleys and cables by clicks; undo, redo; save as scene JSON.");
    if (ImGui::CollapsingHeader("View")) viewPanel(sandbox);
    if (ImGui::CollapsingHeader("Integration")) integrationPanel(sandbox);
    sandbox.panelOverflow[0] = rowOverflow();
  }
  ImGui::End();
}

void inspectorPanel(Sandbox& sandbox, PanelState& state, float top) {
  // A cable clicked in the view opens a collapsed Inspector: its tensions are what the scenes'
  // "what to try" asks to watch (the Inspector starts collapsed on a narrow window).
  if (sandbox.showInspector) ImGui::SetNextWindowCollapsed(false, ImGuiCond_Always);
  sandbox.showInspector = false;
  sandbox.inspectorOpen = beginSidePanel(sandbox, state, "Inspector", false, top);
  if (sandbox.inspectorOpen) {
    sandbox.cutHeaders = 0;
    inspectorContents(sandbox);
    sandbox.panelOverflow[1] = std::max(rowOverflow(), sandbox.cutHeaders);
  }
  ImGui::End();
}

void statusLine(Sandbox& sandbox) {
  const float h = kStatusHeight * sandbox.uiScale;
  ImGui::SetNextWindowPos(ImVec2(0, sandbox.camera.height - h));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(sandbox.camera.width), h));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar |
                   ImGuiWindowFlags_NoSavedSettings | kPanelBackground);
  record(sandbox);
  if (const World* world = sandbox.world()) {
    // The whole line when it fits, else without the timings, else without the note, else the
    // essentials.
    const StepStats& s = world->lastStepStats();
    const char* state = sandbox.paused ? "PAUSED" : "running";
    const char* note = sandbox.message.empty() ? "h: help" : sandbox.message.c_str();
    const std::string energy = energyReadout(world->energy());
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s %.2gx  t %.3f s   energy %s J   step %.1f us (cables %.1f us)   %.0f fps   "
                  "wraps %d   %s",
                  state, sandbox.speed, world->time(), energy.c_str(), s.stepMicros, s.cableMicros,
                  sandbox.fps, s.wrapPoints, note);
    const float room = ImGui::GetContentRegionAvail().x;
    // In presentation mode without the timings: the hall reads the time and the energy.
    if (sandbox.presentation || ImGui::CalcTextSize(line).x > room)
      std::snprintf(line, sizeof line, "%s %.2gx  t %.3f s   energy %s J   %s", state,
                    sandbox.speed, world->time(), energy.c_str(), note);
    // Closer together, without the speed, before without the note (a saved clip's name).
    if (ImGui::CalcTextSize(line).x > room)
      std::snprintf(line, sizeof line, "%s  t %.2f s  energy %s J  %s", state, world->time(),
                    energy.c_str(), note);
    // Without the note before without the energy: the energy readout is what a lecture reads.
    if (ImGui::CalcTextSize(line).x > room)
      std::snprintf(line, sizeof line, "%s %.2gx  t %.3f s   energy %s J", state, sandbox.speed,
                    world->time(), energy.c_str());
    if (ImGui::CalcTextSize(line).x > room)
      std::snprintf(line, sizeof line, "%s  t %.2f s", state, world->time());
    sandbox.statusOverflow = std::max(0.0f, ImGui::CalcTextSize(line).x - room);
    sandbox.shownStatus = line;
    ImGui::TextUnformatted(line);
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

/// A dialog window centred below the menu bar (call ImGui::End() after it).
void beginDialog(Sandbox& sandbox, const char* title, bool* show) {
  ImGui::SetNextWindowPos(ImVec2(0.5f * sandbox.camera.width, 0.15f * sandbox.camera.height),
                          ImGuiCond_Always, ImVec2(0.5f, 0));
  ImGui::SetNextWindowSize(
      ImVec2(std::min(520.0f * sandbox.uiScale, sandbox.camera.width - 20.0f), 0));
  ImGui::Begin(title, show, ImGuiWindowFlags_NoCollapse);
  record(sandbox);
}

/// A path field over the dialog's width, then `action` and Cancel (which closes the dialog);
/// true when the user chose the action (or pressed Enter) with a path in the field.
bool pathRow(const char* id, std::array<char, 512>& path, const char* action, bool& show,
             const char* tip) {
  ImGui::SetNextItemWidth(-1);
  const bool enter =
      ImGui::InputText(id, path.data(), path.size(), ImGuiInputTextFlags_EnterReturnsTrue);
  if (tip) tooltip(tip);
  const bool chosen = (ImGui::Button(action) || enter) && path[0] != '\0';
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) show = false;
  return chosen;
}

void openDialog(Sandbox& sandbox, PanelState& state) {
  if (!state.showOpen) return;
  beginDialog(sandbox, "Open scene file", &state.showOpen);
  ImGui::TextUnformatted("Bundled scenes (assets/scenes):");
  for (const std::string& f : bundledSceneFiles())
    if (ImGui::Selectable(f.c_str())) copyPath(state.openPath, f);
  ImGui::TextUnformatted("Path of a scene JSON file (or a built-in scene name):");
  if (pathRow("##path", state.openPath, "Open", state.showOpen,
              "A file, relative to the working directory, or a built-in name such as hexagon.") &&
      sandbox.open(state.openPath.data()))
    state.showOpen = false;
  ImGui::End();
}

void saveDialog(Sandbox& sandbox, PanelState& state) {
  if (!state.showSave) return;
  beginDialog(sandbox, "Save scene", &state.showSave);
  ImGui::TextUnformatted("Scene JSON file to write (`cablelab run FILE` runs it):");
  if (pathRow("##save", state.savePath, "Save", state.showSave, nullptr)) {
    try {
      saveScene(sandbox, state.savePath.data());
      sandbox.sceneFile = state.savePath.data();  // its name is the scene's now
      sandbox.message = std::string("saved ") + state.savePath.data();
      state.showSave = false;
    } catch (const std::exception& e) {
      sandbox.error = e.what();
    }
  }
  ImGui::End();
}

void errorBanner(Sandbox& sandbox) {
  if (sandbox.error.empty()) return;
  const float w = static_cast<float>(sandbox.camera.width), gap = 8 * sandbox.uiScale;
  float left = 0.5f * w, width = std::min(600.0f * sandbox.uiScale, w - 40.0f), pivot = 0.5f;
  // A value the Build menu's field refused: the box goes right of the open menu, which stays
  // open for the student to type again (a box over it hid the field).
  const BuildMenuLayout& menu = sandbox.authoring->menu;
  if (menu.open) {
    const float menuRight =
        std::max(menu.popup.x + menu.popup.width,
                 menu.nextBodyOpen ? menu.nextBodyPopup.x + menu.nextBodyPopup.width : 0.0f) +
        gap;
    if (w - gap - menuRight >= 12 * ImGui::GetFontSize()) {
      left = menuRight;
      width = std::min(width, w - gap - menuRight);
      pivot = 0;
    }
  }
  ImGui::SetNextWindowPos(ImVec2(left, 40 * sandbox.uiScale), ImGuiCond_Always, ImVec2(pivot, 0));
  ImGui::SetNextWindowSize(ImVec2(width, 0));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(255, 228, 228, 245));
  // Not focused when it appears: focusing a window closes the open menus.
  ImGui::Begin("Error", nullptr,
               ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoFocusOnAppearing);
  record(sandbox);
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  sandbox.errorBox = {pos.x, pos.y, size.x, size.y};
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
  sandbox.errorBox = sandbox.speedSlider = sandbox.speedValue = sandbox.recordButton =
      PanelRect{};  // drawn this frame
  layoutFor(sandbox, state);
  const float top = menuBar(sandbox, state);
  if (!sandbox.presentation) {
    simulationPanel(sandbox, state, top);
    inspectorPanel(sandbox, state, top);
  }
  statusLine(sandbox);
  helpOverlay(sandbox);
  openDialog(sandbox, state);
  saveDialog(sandbox, state);
  errorBanner(sandbox);
}

}  // namespace cablelab::ui
