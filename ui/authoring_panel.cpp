// The Build section of the Simulation panel and the authoring overlay (ui/authoring.h).
#include <imgui.h>
#include <imgui_internal.h>  // the open menu's rows and scroll (ImGuiWindow)

#include <algorithm>
#include <array>
#include <utility>

#include "ui/authoring.h"
#include "ui/panels.h"
#include "ui/typed_field.h"

namespace cablelab::ui {
namespace {

constexpr Colour kDraft{0.1f, 0.45f, 0.2f, 1.0f};

using Tool = Authoring::Tool;

/// Every tool with its tooltip, in the buttons' and the Build menu's order.
const std::array<std::pair<Tool, const char*>, Authoring::kToolCount>& toolTips() {
  static const std::array<std::pair<Tool, const char*>, Authoring::kToolCount> tools = {{
      {Tool::None, "Clicks select and drag, as usual."},
      {Tool::Box, "Click to add a box."},
      {Tool::Circle, "Click to add a circle (a ball, a wheel)."},
      {Tool::Polygon, "Click the corners, then Finish (or right click): their convex hull."},
      {Tool::PointPulley,
       "Click to add an eyelet the cable runs through. On a body it moves with the body."},
      {Tool::PolygonPulley,
       "Click to add a hexagon the cable wraps. On a body it turns on an axle there."},
      {Tool::CirclePulley,
       "Click to add a round pulley the cable wraps. On a body it turns on an axle there."},
      {Tool::Cable,
       "Click the start (a point on a body, or empty space), the pulleys in order, then the end. "
       "Shift+click: any body as a pulley. Alt+click: an eyelet on any body. Right click "
       "cancels."},
      {Tool::Revolute,
       "Click two bodies: they turn about the second click (empty space: the "
       "ground)."},
      {Tool::Prismatic, "Click two bodies: they slide along a line through the second click."},
      {Tool::Weld, "Click two bodies: they are glued together at the second click."},
      {Tool::Delete, "Click a body or a cable to delete it (with its cables and joints)."},
  }};
  return tools;
}

void toolButtons(Authoring& a) {
  for (const auto& [tool, tip] : toolTips()) {
    if (tool != Tool::None) sameLineIfRoom(checkboxWidth(toolName(tool)));
    if (ImGui::RadioButton(toolName(tool), a.tool == tool)) chooseTool(a, tool);
    tooltip(tip);
  }
}

/// The next body's size, mass and type; `menu`: the Build menu's layout, to record the fields'
/// rectangles in (null in the panel). A typed size or mass it cannot take leaves the field as it
/// was and puts one line in `complaint` (ui/typed_field.h).
void bodySettings(Authoring& a, std::string* complaint, BuildMenuLayout* menu = nullptr) {
  float size = static_cast<float>(a.size), mass = static_cast<float>(a.mass);
  ImGui::SetNextItemWidth(fieldWidth("size (m)", ImGui::GetFontSize() * 5));
  if (typedDrag("next body", "size (m)", &size, 0.01f, 0.02f, 10.0f, "%.2f", complaint))
    a.size = size;
  if (menu) menu->size = lastItemRect();
  tooltip("Box side, circle and pulley diameter.");
  sameLineIfRoom(ImGui::GetFontSize() * 4 + checkboxWidth("kg") - ImGui::GetFrameHeight());
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 4);
  if (typedDrag("next body", "kg", &mass, 0.05f, 0.01f, 1000.0f, "%.2f", complaint)) a.mass = mass;
  if (menu) menu->mass = lastItemRect();
  tooltip("Mass of the next body (and of a pulley put on a body).");
  static const std::array<std::pair<BodyType, const char*>, 3> types = {
      {{BodyType::Dynamic, "moves"}, {BodyType::Static, "fixed"}, {BodyType::Kinematic, "driven"}}};
  static const char* const tips[] = {
      "The next body falls, swings and is pulled by cables.",
      "The next body never moves (a wall, a ground).",
      "The next body moves at the speed you give it in the Inspector, whatever pushes on it."};
  for (size_t k = 0; k < types.size(); ++k) {
    // A menu grows to its widest row: there the three share one row (they wrapped before).
    if (k && menu)
      ImGui::SameLine();
    else if (k)
      sameLineIfRoom(checkboxWidth(types[k].second));
    if (ImGui::RadioButton(types[k].second, a.bodyType == types[k].first))
      a.bodyType = types[k].first;
    tooltip(tips[k]);
  }
  ImGui::Checkbox("ends wind on circles", &a.drumEnds);  // fits the panel at projector scale
  tooltip("A cable end clicked on a circle is wound round it, like a rope on a winch drum.");
}

}  // namespace

void authoringPanel(Sandbox& sandbox) {
  Authoring& a = *sandbox.authoring;
  toolButtons(a);
  bodySettings(a, &sandbox.error);
  if (a.tool == Authoring::Tool::Polygon) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Finish")) finishPolygon(sandbox);
    tooltip("Make the polygon from the corners clicked so far.");
  }
  if (ImGui::Button("Undo")) undoEdit(sandbox);
  tooltip("Undo the last edit (Ctrl+Z).");
  sameLineIfRoom(buttonWidth("Redo"));
  if (ImGui::Button("Redo")) redoEdit(sandbox);
  tooltip("Redo the edit undone last (Ctrl+Y).");
  sameLineIfRoom(buttonWidth("New"));
  if (ImGui::Button("New")) newScene(sandbox);
  tooltip("An empty scene with a ground (undo brings the old one back).");
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%zu undo, %zu redo; Scene > Save scene as...", a.undo.size(), a.redo.size());
  ImGui::PopStyleColor();
}

namespace {

/// The current window's rectangle (px).
PanelRect windowRect() {
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  return {pos.x, pos.y, size.x, size.y};
}

/// Records how much of the current menu's rows is cut: past its right edge, or scrolled out of
/// sight below (a menu taller than the window gets a scroll bar).
void recordCut(BuildMenuLayout& layout) {
  const ImGuiWindow* w = ImGui::GetCurrentWindow();
  layout.rowOverflow =
      std::max(layout.rowOverflow, std::max(0.0f, w->DC.CursorMaxPos.x - w->WorkRect.Max.x));
  layout.hiddenHeight = std::max(layout.hiddenHeight, w->ScrollMax.y);
}

/// The next body's settings as a submenu.
void nextBodyMenu(Sandbox& sandbox, BuildMenuLayout& layout) {
  Authoring& a = *sandbox.authoring;
  // A short label: a longer one widens the whole menu (onto the PAUSED sign at 1280x720).
  layout.nextBodyOpen = ImGui::BeginMenu("next body");
  if (!layout.nextBodyOpen) {
    layout.nextBody = lastItemRect();  // open, it keeps the rectangle it had closed
    tooltip("The size, mass and kind of the next body or pulley you add.");
    return;
  }
  layout.nextBodyPopup = windowRect();
  bodySettings(a, &sandbox.error, &layout);
  recordCut(layout);
  ImGui::EndMenu();
}

}  // namespace

void buildMenu(Sandbox& sandbox) {
  Authoring& a = *sandbox.authoring;
  BuildMenuLayout& layout = a.menu;
  layout.open = ImGui::BeginMenu("Build");
  if (!layout.open) {
    const PanelRect title = lastItemRect();
    layout = BuildMenuLayout{};
    layout.title = title;
    return;
  }
  layout.popup = windowRect();
  layout.tools.assign(Authoring::kToolCount, PanelRect{});
  layout.nextBodyPopup = layout.size = layout.mass = PanelRect{};
  layout.rowOverflow = layout.hiddenHeight = 0;
  if (ImGui::MenuItem("New scene")) newScene(sandbox);
  layout.newScene = lastItemRect();
  tooltip("An empty scene with a ground, paused (undo brings the old one back).");
  ImGui::Separator();
  for (const auto& [tool, tip] : toolTips()) {
    if (ImGui::MenuItem(toolName(tool), tool == Tool::None ? "Esc" : nullptr, a.tool == tool))
      chooseTool(a, tool);
    layout.tools[static_cast<size_t>(tool)] = lastItemRect();
    tooltip(tip);
  }
  if (a.tool == Tool::Polygon && ImGui::MenuItem("finish the polygon")) finishPolygon(sandbox);
  ImGui::Separator();
  nextBodyMenu(sandbox, layout);
  ImGui::Separator();
  if (ImGui::MenuItem("Undo", "Ctrl+Z", false, !a.undo.empty())) undoEdit(sandbox);
  if (ImGui::MenuItem("Redo", "Ctrl+Y", false, !a.redo.empty())) redoEdit(sandbox);
  recordCut(layout);
  ImGui::EndMenu();
}

void authoringOverlay(const Sandbox& sandbox, Overlay& overlay) {
  const Authoring& a = *sandbox.authoring;
  for (const Vec2& p : a.polygon) overlay.targets.push_back({p, "", kDraft});
  if (!a.cableStarted) return;
  Vec2 from = a.startWorld;
  for (const RouteStop& stop : a.route) {
    overlay.arrows.push_back({from, stop.world, "", kDraft});
    from = stop.world;
  }
  overlay.targets.push_back({a.startWorld, "cable start", kDraft});
  overlay.keys.push_back({Overlay::Key::Marker::Cross, "cable being routed", kDraft});
}

}  // namespace cablelab::ui
