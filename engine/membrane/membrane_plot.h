// Plot data for the membrane fit figures of thesis chapter 3, kept apart from drawing so any
// renderer (the offscreen PNG one, the sandbox, a spreadsheet) can draw it:
//   figure 3-2, quiver: at each contact point, the measured (red) and modelled (black) force
//     directions, plus each measurement mirrored across the band's perpendicular bisector
//     (cyan; the model predicts the mirror image to match);
//   figure 3-3, scatter: measured fy against modelled fy (on the diagonal for a perfect fit).
// Needs: Eigen. No UI.
#pragma once

#include <iosfwd>
#include <vector>

#include "engine/membrane/membrane_data.h"
#include "engine/membrane/membrane_model.h"

namespace cablelab {

/// One arrow site of the quiver plot. Directions are atan2(F_y, F_x) in degrees.
struct MembraneQuiverRow {
  Vec2 p = Vec2::Zero();          ///< contact point, world (m)
  double measuredAngleDeg = 0.0;  ///< measured force direction (degrees)
  double modelAngleDeg = 0.0;     ///< modelled force direction (degrees)
  Vec2 mirrorP = Vec2::Zero();    ///< p reflected across the bisector of AB (m)
  double mirrorAngleDeg = 0.0;    ///< measured direction reflected the same way (degrees)
};

/// One point of the scatter plot.
struct MembraneScatterRow {
  double measuredFy = 0.0;  ///< N
  double modelFy = 0.0;     ///< N
};

struct MembranePlotData {
  std::vector<MembraneQuiverRow> quiver;    ///< one per measurement, file order
  std::vector<MembraneScatterRow> scatter;  ///< one per measurement, file order
};

/// Evaluates the fitted model at every measurement.
MembranePlotData makeMembranePlotData(const MembraneGeometry& g, const MembraneParams& fitted,
                                      const std::vector<MembraneSample>& rows);

/// CSV with header x,y,measured_angle_deg,model_angle_deg,mirror_x,mirror_y,mirror_angle_deg.
void writeQuiverCsv(std::ostream& out, const MembranePlotData& data);

/// CSV with header measured_fy,model_fy.
void writeScatterCsv(std::ostream& out, const MembranePlotData& data);

}  // namespace cablelab
