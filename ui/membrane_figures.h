// The chapter 3 fit figures as plots (ui/plot.h), from the engine's plot data
// (engine/membrane/membrane_plot.h):
//   quiver (thesis figure 3-2): at every deformation point the measured force direction (red)
//     and the fitted model's (black); each measurement mirrored across the band's perpendicular
//     bisector (cyan, the model predicts the mirror image); the pulleys A and B and the straight
//     band between them. Axes in m, equal aspect; arrows are unit directions.
//   scatter (thesis figure 3-3): measured against modelled vertical force (N) with the y = x
//     line; the fitted k and preload in the title.
//
// Needs: ui/plot.h (cablelab_offscreen, for rendering) and the engine's membrane headers.
#pragma once

#include <string>

#include "engine/membrane/membrane_model.h"
#include "engine/membrane/membrane_plot.h"
#include "ui/plot.h"

namespace cablelab::ui {

/// Figure 3-2 for the fitted parameters `fitted` over the pulleys `g`.
Plot membraneQuiverPlot(const MembraneGeometry& g, const MembraneParams& fitted,
                        const MembranePlotData& data);

/// Figure 3-3 for the fitted parameters `fitted`.
Plot membraneScatterPlot(const MembraneParams& fitted, const MembranePlotData& data);

/// Writes DIR/quiver.png and DIR/scatter.png (width x height each); throws std::runtime_error
/// naming the file on failure.
void writeMembraneFigures(const MembraneGeometry& g, const MembraneParams& fitted,
                          const MembranePlotData& data, const std::string& dir, int width,
                          int height);

}  // namespace cablelab::ui
