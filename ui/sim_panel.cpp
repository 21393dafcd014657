// The Simulation panel's sections: Scene, Run, Integration, View (ui/panel_sections.h).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ui/clip.h"
#include "ui/input.h"
#include "ui/panel_sections.h"
#include "ui/scene_catalog.h"
#include "ui/scene_guide.h"
#include "ui/typed_field.h"

namespace cablelab::ui {

namespace {

void parameterSliders(Sandbox& sandbox) {
  const auto params = sceneParameters(sandbox.sceneName);
  if (params.empty()) {
    ImGui::TextDisabled("a scene file: no parameters (edit the JSON)");
    return;
  }
  bool apply = false;
  auto values = sandbox.parameters;
  for (const SceneParameter& p : params) {
    auto it =
        std::find_if(values.begin(), values.end(), [&](auto& v) { return v.first == p.name; });
    if (it == values.end()) it = values.insert(values.end(), {p.name, p.value});
    float v = static_cast<float>(it->second);
    // The unit next to the slider ("m_load (kg)"), from the description's last "(...)".
    const size_t open = p.description.rfind(" (");
    const std::string unit =
        open != std::string::npos && p.description.back() == ')' ? p.description.substr(open) : "";
    const std::string label = p.name + unit + "###" + p.name;
    ImGui::SetNextItemWidth(fieldWidth((p.name + unit).c_str(), ImGui::GetFontSize() * 9));
    const ImGuiSliderFlags flags = p.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
    if (ImGui::SliderFloat(label.c_str(), &v, static_cast<float>(p.lo), static_cast<float>(p.hi),
                           "%.4g", flags))
      it->second = v;
    apply |= ImGui::IsItemDeactivatedAfterEdit();
    tooltip(parameterTip(p.description, p.value).c_str());
  }
  if (apply) sandbox.rebuild(values);
  if (ImGui::SmallButton("Defaults")) {
    values.clear();
    for (const SceneParameter& p : params) values.emplace_back(p.name, p.value);
    sandbox.rebuild(values);
  }
  tooltip("Rebuild the scene with every parameter at its default.");
}

}  // namespace

void scenePanel(Sandbox& sandbox) {
  const std::string title = sandbox.displayName();
  ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(20, 60, 140, 255));
  ImGui::TextUnformatted(title.c_str());
  ImGui::PopStyleColor();
  // A built-in scene's description for students (ui/scene_guide.h), a file's own; whole.
  const std::string student = studentDescription(sandbox.sceneName);
  const std::string& shown = student.empty() ? sandbox.scene.description : student;
  ImGui::PushTextWrapPos(0);
  if (!shown.empty()) ImGui::TextUnformatted(shown.c_str());
  ImGui::PopTextWrapPos();
  sandbox.shownTitle = title;
  sandbox.shownDescription = shown;
  if (ImGui::TreeNode("What to try")) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(whatToTry(sandbox.sceneName).c_str());
    ImGui::PopTextWrapPos();
    ImGui::TreePop();
  }
  if (ImGui::TreeNode("Parameters")) {
    parameterSliders(sandbox);
    ImGui::TreePop();
  }
}

void runPanel(Sandbox& sandbox) {
  // Three buttons of one width on a row when their words fit, else each as wide as its word,
  // wrapping to the next row (a narrow panel at a large UI scale).
  const char* run = sandbox.paused ? "Play" : "Pause";
  const float widest = std::max({buttonWidth("Pause"), buttonWidth("Step"), buttonWidth("Reset")});
  const float even = (ImGui::GetContentRegionAvail().x - 2 * ImGui::GetStyle().ItemSpacing.x) / 3;
  const float w = even >= widest ? std::min(ImGui::GetFontSize() * 4.5f, even - 1) : 0.0f;
  sandbox.truncatedButtons = 0;
  auto counted = [&](const char* label) {
    sandbox.truncatedButtons += ImGui::GetItemRectSize().x + 0.5f < buttonWidth(label);
  };
  if (ImGui::Button(run, ImVec2(w, 0))) sandbox.paused = !sandbox.paused;
  counted(run);
  tooltip("Run or pause the simulation (space).");
  sameLineIfRoom(std::max(w, buttonWidth("Step")));
  if (ImGui::Button("Step", ImVec2(w, 0))) {
    sandbox.paused = true;
    ++sandbox.pendingSteps;
  }
  counted("Step");
  tooltip("Pause and advance one time step (s).");
  sameLineIfRoom(std::max(w, buttonWidth("Reset")));
  if (ImGui::Button("Reset", ImVec2(w, 0))) sandbox.reset();
  counted("Reset");
  tooltip("Rebuild the scene from its start (r); the tension scale stays as it is.");
  // Speed: a slider over the steps, its value beside it (in the slider the handle hid "00" of
  // "1.00x" at projector scale), plus the step buttons.
  float speed = static_cast<float>(sandbox.speed);
  char value[32];
  std::snprintf(value, sizeof value, "speed %.2fx", sandbox.speed);
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const float buttons = buttonWidth("-") + buttonWidth("+") + buttonWidth("1x") + 3 * spacing;
  ImGui::SetNextItemWidth(std::max(fieldWidth("speed 4.00x", ImGui::GetFontSize() * 8) - buttons,
                                   3 * ImGui::GetFontSize()));
  if (ImGui::SliderFloat("##speed", &speed, 0.1f, 4.0f, "", ImGuiSliderFlags_Logarithmic))
    sandbox.speed = std::clamp(static_cast<double>(speed), 0.1, 4.0);
  const char* speedTip =
      "Simulated seconds per wall second: 0.1x is slow motion, 4x fast forward ([ and ]).";
  tooltip(speedTip);
  sandbox.speedSlider = lastItemRect();
  ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
  ImGui::TextUnformatted(value);
  tooltip(speedTip);
  sandbox.speedValue = lastItemRect();
  sameLineIfRoom(buttonWidth("-"));
  if (ImGui::SmallButton("-")) sandbox.speed = stepSpeed(sandbox.speed, -1);
  tooltip("Slower ([).");
  sameLineIfRoom(buttonWidth("+"));
  if (ImGui::SmallButton("+")) sandbox.speed = stepSpeed(sandbox.speed, +1);
  tooltip("Faster (]).");
  sameLineIfRoom(buttonWidth("1x"));
  if (ImGui::SmallButton("1x")) sandbox.speed = 1;
  tooltip("Real time.");

  if (ImGui::Button("Screenshot")) sandbox.screenshotRequested = true;
  tooltip("Save the window as a PNG in the working directory (F12).");
  const bool recording = sandbox.recording;
  if (recording) ImGui::PushStyleColor(ImGuiCol_Button, IM_COL32(220, 70, 60, 255));
  char label[64];
  std::snprintf(label, sizeof label, recording ? "Stop (%d frames)###rec" : "Record clip###rec",
                sandbox.recordedFrames);
  sameLineIfRoom(buttonWidth(label));
  if (ImGui::Button(label)) sandbox.recordToggleRequested = true;
  if (recording) ImGui::PopStyleColor();
  tooltip(mp4Available()
              ? "Record the world view as an MP4 video (F9), one frame per 1/fps s of simulated "
                "time: it plays at the simulation's own speed. Saved in the working directory."
              : "Record the world view as an animated GIF (F9), one frame per 1/fps s of simulated "
                "time: it plays at the simulation's own speed. Saved in the working directory. "
                "(This build has no FFmpeg, so no MP4.)");
  float fps = static_cast<float>(
      sandbox.recordFps > 0 ? sandbox.recordFps
                            : defaultClipFps(mp4Available() ? ClipFormat::Mp4 : ClipFormat::Gif));
  sameLineIfRoom(ImGui::GetFontSize() * 3.5f + ImGui::GetStyle().ItemInnerSpacing.x +
                 ImGui::CalcTextSize("fps").x);
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 3.5f);
  if (recording) ImGui::BeginDisabled();
  if (typedDrag("Record clip", "fps", &fps, 0.5f, 5, 50, "%.0f", &sandbox.error))
    sandbox.recordFps = std::clamp(static_cast<double>(fps), 5.0, 50.0);
  if (recording) ImGui::EndDisabled();
  tooltip("Clip frames per simulated second (5..50).");
}

void integrationPanel(Sandbox& sandbox) {
  double dtMs = sandbox.dt * 1000;
  ImGui::SetNextItemWidth(fieldWidth("dt (ms)", ImGui::GetFontSize() * 8));
  if (ImGui::InputDouble("dt (ms)", &dtMs, 1, 5, "%.3f")) {
    if (std::isfinite(dtMs) && dtMs > 0.01 && dtMs <= 100)
      sandbox.dt = dtMs / 1000;
    else
      sandbox.error = typedRangeComplaint("Simulation", "dt (ms)", 0.01f, 100, dtMs,
                                          static_cast<float>(sandbox.dt * 1000));
  }
  tooltip("Time step (takes effect at once; Reset keeps it).");
  ImGui::SetNextItemWidth(fieldWidth("substeps", ImGui::GetFontSize() * 8));
  if (ImGui::SliderInt("substeps", &sandbox.substeps, 1, 64))
    sandbox.substeps = std::max(1, sandbox.substeps);
  tooltip("Sub-steps per time step: more is stiffer and slower.");
  float g[2] = {static_cast<float>(sandbox.gravity.x()), static_cast<float>(sandbox.gravity.y())};
  ImGui::SetNextItemWidth(fieldWidth("gravity", ImGui::GetFontSize() * 8));
  if (typedDrag2("Simulation", "gravity", g, 0.05f, -50, 50, "%.2f", &sandbox.error))
    sandbox.gravity = Vec2(g[0], g[1]);
  tooltip("Gravity (m/s^2), x and y.");
  if (ImGui::Button("g = 0")) sandbox.gravity = Vec2::Zero();
  tooltip("Switch gravity off.");
  sameLineIfRoom(buttonWidth("g = -9.81"));
  if (ImGui::Button("g = -9.81")) sandbox.gravity = Vec2(0, -9.81);
  tooltip("Earth gravity, downwards.");
}

namespace {

void drawToggles(Sandbox& sandbox) {
  RenderOptions& d = sandbox.draw;
  struct Toggle {
    const char* label;
    bool* value;
    const char* tip;
  };
  const Toggle toggles[] = {
      {"labels", &d.labels, "Body names."},
      {"grid", &d.grid, "Grid lines and the scale bar."},
      {"wrap points", &d.wrapPoints, "Squares where a cable touches a pulley, discs at its ends."},
      {"tensions", &d.tensions, "Colour the cables by tension (else one plain colour)."},
      {"forces", &d.forces, "Arrows of the cable forces at the cable ends."},
      {"legend", &d.legend, "The tension colour bar."},
      {"marker key", &d.markerLegend, "The key of every marker drawn."},
      {"overstretch", &d.overstretch,
       "Mark cables longer than they should be (rigid: > 1 cm over rest)."},
  };
  // Two columns when the widest toggle fits in half the panel, else one.
  float widest = 0;
  for (const Toggle& t : toggles) widest = std::max(widest, checkboxWidth(t.label));
  const float half = 0.5f * ImGui::GetContentRegionAvail().x;
  const bool twoColumns = widest + ImGui::GetStyle().ItemSpacing.x <= half;
  int k = 0;
  for (const Toggle& t : toggles) {
    if (k++ % 2 && twoColumns) ImGui::SameLine(half + ImGui::GetCursorPosX());
    ImGui::Checkbox(t.label, t.value);
    tooltip(t.tip);
  }
}

}  // namespace

void viewPanel(Sandbox& sandbox) {
  float zoom = static_cast<float>(1.0 / sandbox.camera.metresPerPixel);
  ImGui::SetNextItemWidth(fieldWidth("px per m", ImGui::GetFontSize() * 8));
  if (typedDrag("View", "px per m", &zoom, 1.0f, 1.0f, 100000.0f, "%.0f", &sandbox.error))
    sandbox.camera.metresPerPixel = 1.0 / zoom;
  tooltip("Zoom: screen pixels per metre (the wheel zooms about the cursor).");
  if (ImGui::Button("Fit scene view")) sandbox.fitView();
  tooltip("Fit the scene to the view (v); it stays fitted until you pan or zoom.");
  sameLineIfRoom(checkboxWidth("follow"));
  if (sandbox.selectedBody < 0) ImGui::BeginDisabled();
  ImGui::Checkbox("follow", &sandbox.follow);
  if (sandbox.selectedBody < 0) ImGui::EndDisabled();
  tooltip("The camera keeps the selected body in the middle of the view (f).");
  drawToggles(sandbox);

  if (ImGui::Checkbox("lock tension scale", &sandbox.tensionScaleLocked) &&
      !sandbox.tensionScaleLocked)
    sandbox.tensionScale = sandbox.sceneTensionScale;
  tooltip(
      "The colour bar runs from 0 to the scene's own scale, worked out from its loads (the "
      "weights m g of its moving bodies summed): a run never changes it. Locked, it keeps your "
      "maximum through resets and other scenes, to compare runs colour for colour.");
  float top = static_cast<float>(sandbox.tensionScale);
  ImGui::SetNextItemWidth(fieldWidth("scale max (N)", ImGui::GetFontSize() * 8));
  if (typedDrag("View", "scale max (N)", &top, std::max(top * 0.01f, 0.01f), 0.01f, 1e7f, "%.4g",
                &sandbox.error)) {
    sandbox.tensionScale = std::max(static_cast<double>(top), 1e-3);
    sandbox.tensionScaleLocked = true;  // the user's own maximum: kept until unlocked
  }
  tooltip("Tension (N) at the red end of the colour bar; setting it locks the scale.");

  ImGui::SetNextItemWidth(fieldWidth("drag limit", ImGui::GetFontSize() * 8));
  float drag = static_cast<float>(sandbox.dragWeights);
  if (ImGui::SliderFloat("drag limit", &drag, 0.5f, 20.0f, "%.1f weights"))
    sandbox.dragWeights = drag;
  tooltip(
      "The mouse pulls with at most this many times the body's weight (at least 9.81 "
      "m/s^2), so a cable can hold against it.");
  ImGui::SetNextItemWidth(fieldWidth("UI scale", ImGui::GetFontSize() * 8));
  ImGui::SliderFloat("UI scale", &sandbox.uiScale, 0.75f, 3.0f, "%.2f");
  tooltip("Size of the text and the panels.");
  sameLineIfRoom(checkboxWidth("projector"));
  if (ImGui::Checkbox("projector", &sandbox.projector)) sandbox.uiScale = sandbox.projector ? 2 : 1;
  tooltip("Projector mode: large fonts and thick lines for a lecture hall.");
}

}  // namespace cablelab::ui
