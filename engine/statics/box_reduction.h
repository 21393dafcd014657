// Box-to-point reduction of thesis figure 4-2 (docs/model.md#box-reduction).
//
// A box that translates but does not rotate touches each cable at known corners. The cable
// runs fingertip a -> corner cA -> (along the box) -> corner cB -> fingertip b, with corners at
// box position x plus fixed offsets oA, oB. Its length is
//   |x + oA - a| + |oB - oA| + |b - x - oB| = |x - (a - oA)| + |x - (b - oB)| + |oB - oA|,
// the length of a point cable with fingertips shifted by the corner offsets and a rest length
// shortened by the fixed corner-to-corner run. So the box's equilibrium position x is the
// point problem's minimiser. The reduced rest length may be negative (a cable shorter than the
// run around the box is stretched wherever the box is); the solvers accept that.
#pragma once

#include <vector>

#include "engine/statics/statics.h"

namespace cablelab {

/// A cable pressing on the box.
struct BoxCable {
  Vec2 a = Vec2::Zero();        ///< first fingertip point (m)
  Vec2 b = Vec2::Zero();        ///< second fingertip point (m)
  double k = 1.0;               ///< stiffness (N/m)
  double L = 0.0;               ///< rest length (m)
  Vec2 cornerA = Vec2::Zero();  ///< offset from the box position of the corner the a-side
                                ///< segment touches (m)
  Vec2 cornerB = Vec2::Zero();  ///< offset of the corner the b-side segment leaves from (m);
                                ///< equal to cornerA for a single contact
};

/// The point cable equivalent to `cable` for the box position.
StaticsCable reduceBoxCable(const BoxCable& cable);

/// The point problem whose minimiser is the box position (p0: the box's initial position).
StaticsProblem reduceBoxToPoint(const std::vector<BoxCable>& cables,
                                std::optional<Vec2> boxPosition = std::nullopt);

}  // namespace cablelab
