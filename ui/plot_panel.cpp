// The Plots section of the Simulation panel (ui/plot_panel.h).
#include "ui/plot_panel.h"

#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "ui/controller_panel.h"
#include "ui/panels.h"
#include "ui/plot_board.h"
#include "ui/plot_draw.h"
#include "ui/plot_image.h"

namespace cablelab::ui {
namespace {

/// cablelab-SCENE-plot-N, the first N with neither a .png nor a .csv in the working directory.
std::string freshStem(const std::string& base) {
  for (int n = 1;; ++n) {
    const std::string stem = "cablelab-" + base + "-plot-" + std::to_string(n);
    if (!std::filesystem::exists(stem + ".png") && !std::filesystem::exists(stem + ".csv"))
      return stem;
  }
}

/// The quantity picker: a combo over what the world offers, and where to put it.
void picker(Sandbox& sandbox, const World& world) {
  static int chosen = 0;  // the picker's row; one sandbox per process
  PlotBoard& board = *sandbox.plots;
  const auto options = availableQuantities(world, controlledBody(sandbox));
  chosen = std::clamp(chosen, 0, static_cast<int>(options.size()) - 1);
  ImGui::SetNextItemWidth(fieldWidth("##quantity", ImGui::GetFontSize() * 12));
  if (ImGui::BeginCombo("##quantity", quantityName(world, options[chosen]).c_str())) {
    for (size_t i = 0; i < options.size(); ++i) {
      const std::string label =
          quantityName(world, options[i]) + " (" + quantityUnit(options[i].kind) + ")";
      if (ImGui::Selectable(label.c_str(), static_cast<int>(i) == chosen))
        chosen = static_cast<int>(i);
    }
    ImGui::EndCombo();
  }
  tooltip(
      "What to plot against time: a body's position, velocity or angle, a cable's length "
      "or tension, the energy, or the controller's error.");
  if (ImGui::SmallButton("New chart")) board.addCurve(board.charts.size(), options[chosen]);
  tooltip("Plot it in a chart of its own.");
  if (!board.charts.empty()) {
    sameLineIfRoom(buttonWidth("Add to last chart"));  // a row of its own in a narrow panel
    if (ImGui::SmallButton("Add to last chart")) {
      const size_t last = board.charts.size() - 1;
      const std::string lastUnit = quantityUnit(board.charts[last].curves[0].kind);
      if (board.addCurve(last, options[chosen]) != last)
        sandbox.message = quantityName(world, options[chosen]) + " is in " +
                          quantityUnit(options[chosen].kind) + ", the last chart in " + lastUnit +
                          ": it has a chart of its own";
    }
    tooltip(
        "Plot it with the last chart's curves (same time axis); a quantity in another unit "
        "gets a chart of its own, so each chart's axis has one unit.");
  }
}

void chartView(Sandbox& sandbox, const World& world, size_t index) {
  PlotBoard& board = *sandbox.plots;
  const Chart& chart = board.charts[index];
  // In the narrow panel: the title as wrapped text above, the legend as the coloured curve list
  // below (both as the PNG has them, which has the room).
  Plot plot = board.plot(chart, world, world.time());
  ImGui::TextWrapped("%s", plot.title.c_str());
  plot.title.clear();
  for (PlotSeries& s : plot.series) s.label.clear();
  const float width = ImGui::GetContentRegionAvail().x;
  const float height = std::round(0.62f * width);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height),
                      IM_COL32(255, 255, 255, 255));
  try {
    drawPlot(draw, plot, static_cast<int>(width), static_cast<int>(height),
             ImGui::GetFontSize() / 13.0f, origin);
  } catch (const std::exception&) {
    // Too narrow to draw: the panel is being resized.
  }
  ImGui::Dummy(ImVec2(width, height));
  ImGui::PushID(static_cast<int>(index));
  if (ImGui::SmallButton("Export PNG + CSV")) {
    try {
      sandbox.message = exportChart(sandbox, index, freshStem(sandbox.fileStem()));
    } catch (const std::exception& e) {
      sandbox.error = e.what();
    }
  }
  tooltip(
      "Save this chart for a slide: a 1920 x 1080 PNG and its numbers as CSV, in the "
      "working directory.");
  for (size_t k = 0; k < chart.curves.size(); ++k) {
    ImGui::PushID(static_cast<int>(k));
    const bool remove = ImGui::SmallButton("x");
    tooltip("Remove this curve.");
    ImGui::SameLine();
    const Colour c = plotColour(static_cast<int>(k));
    ImGui::PushTextWrapPos(0);  // a long body name wraps rather than running past the panel
    ImGui::TextColored(ImVec4(c[0], c[1], c[2], c[3]), "%s (%s)",
                       quantityName(world, chart.curves[k]).c_str(),
                       quantityUnit(chart.curves[k].kind));
    ImGui::PopTextWrapPos();
    ImGui::PopID();
    if (remove) {
      board.removeCurve(index, k);
      break;
    }
  }
  ImGui::PopID();
}

}  // namespace

int controlledBody(const Sandbox& sandbox) {
  const HandControlState* h = sandbox.controller ? sandbox.controller->hand.get() : nullptr;
  return h && h->grasp ? h->box() : -1;
}

void plotsAfterStep(Sandbox& sandbox) {
  if (sandbox.plots && sandbox.world())
    sandbox.plots->record(*sandbox.world(), sandbox.target, controlledBody(sandbox));
}

std::string exportChart(const Sandbox& sandbox, size_t chart, const std::string& stem, int width,
                        int height) {
  const World* world = sandbox.world();
  if (!world || chart >= sandbox.plots->charts.size())
    throw std::runtime_error("no chart to export");
  const Plot plot = sandbox.plots->plot(sandbox.plots->charts[chart], *world, world->time());
  writePng(renderPlotImage(plot, width, height), stem + ".png");
  writePlotCsv(plot, stem + ".csv");
  return "saved " + stem + ".png and " + stem + ".csv";
}

void plotsPanel(Sandbox& sandbox) {
  const World* world = sandbox.world();
  if (!world || !sandbox.plots) return;
  PlotBoard& board = *sandbox.plots;
  picker(sandbox, *world);
  float seconds = static_cast<float>(board.windowSeconds);
  ImGui::SetNextItemWidth(fieldWidth("shown", ImGui::GetFontSize() * 8));
  if (ImGui::SliderFloat("shown", &seconds, 1, static_cast<float>(PlotBoard::kKeptSeconds),
                         "%.0f s"))
    board.windowSeconds = seconds;
  tooltip(
      "How many seconds the charts show, up to the moment on screen (the last 30 s are "
      "kept). The vertical range fits what is shown.");
  for (size_t i = 0; i < board.charts.size(); ++i) chartView(sandbox, *world, i);
}

}  // namespace cablelab::ui
