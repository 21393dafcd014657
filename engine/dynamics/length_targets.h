// The rigid-cable length targets of both cable solves (the main one and the midpoint one): a
// share of the length error is fixed per step; an error below the slop is left alone. Box2D keeps
// positions in float (about 1e-7 m at 1 m): correcting below that only amplifies rounding, by
// beta / h^2 in the tension. Private to engine/dynamics.
#pragma once

namespace cablelab {

inline constexpr double kBaumgarte = 0.2;  ///< share of a rigid cable's length error fixed per step
inline constexpr double kLengthSlop = 1e-5;  ///< m

}  // namespace cablelab
