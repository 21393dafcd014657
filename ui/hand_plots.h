// The hand's three live plots (membrane tensions, tracking error, box position) as charts for a
// slide: the Controller section's "Export PNG" writes each at 1920 x 1080 with its title, axes,
// ticks, units and legend (ui/plot_image.h), where it copied the panel's thumbnails (no ticks,
// one membrane's tension drawn over the other's).
//
// Needs: ui/controller_panel.h (the hand's history) and ui/plot_image.h; no GL.
#pragma once

#include <string>
#include <vector>

#include "ui/controller_panel.h"
#include "ui/plot.h"

namespace cablelab::ui {

/// The hand's plots as drawn in the panel, from `h`'s history: tensions on 0..`tensionTop` N
/// (the colour bar's range), the error, the box's x and y with the targets dashed. The bottom
/// membrane's tension is dashed, so that the top one shows where they are equal (a grasp).
std::vector<Plot> handPlots(const HandControlState& h, double tensionTop);

/// Writes handPlots() as `stem`-tensions.png, `stem`-error.png and `stem`-position.png at
/// width x height; returns the paths. Throws std::runtime_error when a file cannot be written.
std::vector<std::string> exportHandPlots(const HandControlState& h, double tensionTop,
                                         const std::string& stem, int width = 1920,
                                         int height = 1080);

}  // namespace cablelab::ui
