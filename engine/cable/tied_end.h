// A cable end tied to the polygon pulley it winds round (a spool: docs/cables.md, "A rope tied to
// its spool").
//
// The end is fixed on the polygon's own body, on or inside its hull, so no taut path round the
// polygon into it exists (wrapChain's terminal would lie in the hull). The cable instead leaves
// the hull at a fixed corner, the one before the end walking round the polygon from the free end
// of the cable, and runs along that corner's edge to the end. Its wrap is the angle the path
// turns from the free end's segment to that edge, kept continuous over time (whole turns
// included), so each turn of the spool winds one perimeter more.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "engine/core/math.h"
#include "engine/model/scene.h"

namespace cablelab {

/// The corner a cable tied at `end` (the polygon's frame, like `polygon`) leaves the hull at,
/// walking round the convex CCW polygon with it on the cable's `side` towards the end: the first
/// vertex of the edge nearest the end, or the one before it when the end is at that vertex. -1
/// when the end lies outside the hull by more than a small tolerance (an ordinary terminal).
/// `inside`: the end lies in the hull's interior, off every edge.
int tiedEndCorner(const Vec2& end, std::span<const Vec2> polygon, WrapSide side, bool& inside);

/// The chain of a cable from A round the polygon on `side` to an end tied on it that the cable
/// reaches from corner `corner` (tiedEndCorner): the walk from A's tangent vertex to `corner`
/// plus the whole loops that put the angle the path turns (from A's segment to the corner's edge)
/// nearest `reference`. Returns that angle; the chain is empty when it is <= 0 (the cable runs
/// straight from A to the end). A pressed into the hull (a weight wound up to its spool, which
/// the polygon cannot touch) keeps `held`, the chain's first vertex at the last update, as its
/// tangent vertex, so the length stays continuous; nullopt when A lies inside with none held (-1).
std::optional<double> wrapChainToTiedEnd(const Vec2& a, std::span<const Vec2> polygon,
                                         WrapSide side, int corner, double reference, int held,
                                         std::vector<int>& chain);

}  // namespace cablelab
