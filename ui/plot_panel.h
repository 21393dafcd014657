// The Simulation panel's Plots section (ui/plot_board.h): pick quantities, see them against
// time, export each chart as a slide-size PNG (1920 x 1080, ui/plot_image.h) and as CSV.
//
// Needs: Dear ImGui with a window open, a Sandbox.
#pragma once

#include <string>

#include "ui/sandbox.h"

namespace cablelab::ui {

/// The section's widgets and charts.
void plotsPanel(Sandbox& sandbox);

/// Samples the charts after a step (Sandbox::afterStep calls it).
void plotsAfterStep(Sandbox& sandbox);

/// The body the controller steers (the hand's box), -1 if none: its "controller error".
int controlledBody(const Sandbox& sandbox);

/// Writes chart `chart` as PNG (width x height) and CSV to `stem`.png / `stem`.csv; the message
/// names both files. Throws std::runtime_error on failure.
std::string exportChart(const Sandbox& sandbox, size_t chart, const std::string& stem,
                        int width = 1920, int height = 1080);

}  // namespace cablelab::ui
