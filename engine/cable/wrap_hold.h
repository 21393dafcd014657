// Polygons side by side and points pressed into a hull (docs/cables.md, "Points inside a hull"):
// the common tangent of two neighbouring polygons on one cable, and a chain end that a terminal
// inside the polygon's hull holds, so that the length stays continuous where no taut path exists.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "engine/core/math.h"
#include "engine/model/scene.h"

namespace cablelab {

/// The common tangent of two neighbouring polygons on one cable: the segment first[from] ->
/// second[into] with each polygon on its wrap side (on the cable's right for Left), the taut
/// cable's segment between them. False when none exists (opposite sides on overlapping hulls,
/// or one hull inside the other).
bool commonTangent(std::span<const Vec2> first, WrapSide firstSide, std::span<const Vec2> second,
                   WrapSide secondSide, int& from, int& into);

/// A polygon's chain kept from one update to the next: its first vertex at the last update (-1:
/// none) and how many vertices it had, whole laps included (its two end vertices alone cannot tell
/// one vertex from one vertex and a lap), and whether each end is held (its terminal went inside
/// the hull, or it has not yet met the tangent vertex again since it came out).
struct ChainHold {
  int from = -1, count = 0;
  bool holdingFrom = false, holdingInto = false;
  /// The angle the path turns at each held end vertex (rad, in the wrap sense), continued over
  /// time: past half a turn the terminal went through the hull and the rope doubles back there.
  double turnFrom = 0, turnInto = 0;
};

/// wrapChainTurning for a polygon whose terminal may lie inside its hull. An end whose terminal
/// is inside (and `mayHoldFrom` / `mayHoldInto` allow it), or that is held already, continues from
/// its vertex at the last update one vertex at a time, as a wrap point does on the old path: it
/// leaves when it no longer bends the path, the next vertex joins when it reaches the wrap side
/// of the segment to an outside terminal that the segment does not pass through the hull to. It
/// is let go once it is the tangent vertex again. `hold` is updated; nullopt when a terminal is
/// inside with nothing to hold (the polygon has to be dropped).
std::optional<double> wrapChainHeld(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                                    WrapSide side, double reference, bool mayHoldFrom,
                                    bool mayHoldInto, ChainHold& hold, std::vector<int>& chain);

}  // namespace cablelab
