// Taut cable path around one convex polygon pulley (thesis section 2.4.3,
// docs/model.md#wrap-points).
//
// For terminals A and B and a winding side, the taut path is the chain of the convex hull of
// {A, B, polygon vertices} on that side. It is a pure function of the geometry. Collinear points
// are not part of the chain (they would add a wrap point that changes neither length nor J).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "engine/core/math.h"
#include "engine/core/polygon.h"
#include "engine/model/scene.h"

namespace cablelab {

/// Vertex indices (into `polygon`) the taut path A -> ... -> B touches, in path order.
/// Left: the cable passes on the left of the polygon walking from A to B.
/// Returns nullopt when a terminal lies inside the polygon's hull (no taut path exists).
std::optional<std::vector<int>> wrapChain(const Vec2& a, const Vec2& b,
                                          std::span<const Vec2> polygon, WrapSide side);
/// The same into `chain` (reusing its storage); false when no taut path exists.
bool wrapChain(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon, WrapSide side,
               std::vector<int>& chain);

/// The chain of a polygon the cable is wrapped on, kept continuous over time: the walk between
/// the tangent vertices from A and into B, plus as many whole loops round the polygon as put the
/// angle the path turns round it nearest `reference` (rad, its value at the last update; 0 for a
/// polygon that just joined). So a polygon swung round past an end anchor stays wrapped (more than
/// half a turn, more than whole turns), and the chain grows and shrinks one vertex at a time.
/// Returns that angle (the chain is empty when it is <= 0: the path no longer bends round the
/// polygon); nullopt when a terminal lies inside the polygon. With reference 0 it is wrapChain's
/// hull chain wherever that turns the path by less than half a turn.
std::optional<double> wrapChainTurning(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                                       WrapSide side, double reference, std::vector<int>& chain);

/// wrapChainTurning's angle for known tangent vertices ta (from A) and tb (into B): the turn
/// along the walk ta -> tb (`walk` vertices, one lap at most) plus the `loops` whole loops that
/// put it nearest `reference`. At most the straight threshold (1e-12 rad): min(angle, 0), the
/// chain would be empty.
double walkTurning(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon, WrapSide side,
                   int ta, int tb, double reference, int& walk, int& loops);
/// Turns below this (rad) are straight: no vertex is a wrap point.
inline constexpr double kStraightWrapTurn = 1e-12;

/// Length of the path A -> polygon[chain...] -> B.
double chainLength(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon,
                   const std::vector<int>& chain);

/// Signed distance of p from the directed line a->b, positive on the side the pulley must reach to
/// be wrapped (the cable's right for Left, its left for Right).
double wrapSideDistance(const Vec2& a, const Vec2& b, const Vec2& p, WrapSide side);

/// The turn (rad) of a cable that arrives along `in` and leaves along `out` round a point pulley
/// on `side`, continued from `previous` (its turn at the last update) across the +-pi cut: past
/// half a turn (the cable doubled back round the point, e.g. swung round past an end anchor) it
/// goes on growing instead of flipping sign. The point leaves the path when it goes below 0.
double continuedPointTurn(const Vec2& in, const Vec2& out, WrapSide side, double previous);

/// True when p lies strictly inside the convex CCW polygon.
bool insideConvex(const Vec2& p, std::span<const Vec2> polygon);

/// The tangent vertex of the taut path from `terminal` round the polygon on `side` (`into`
/// false), or into `terminal` (`into` true); -1 when the terminal lies inside the polygon.
int tangentVertex(const Vec2& terminal, std::span<const Vec2> polygon, WrapSide side, bool into);

/// How far (m) a point or corner read off Box2D's float poses may lie from where it is, for
/// coordinates up to `scale` (m): a few float roundings of the position and of the angle's lever.
double poseRounding(double scale);

/// The tangent vertex of a terminal that lies in the polygon no deeper than `tolerance` (m) from
/// a face: on that face, where the rope reaches it along the face from the corner behind it on
/// the walk (`into`) or leaves it along the face to the corner ahead (`into` false). -1 when the
/// terminal is outside or deeper in (docs/cables.md, "Points inside a hull").
int tangentVertexOnFace(const Vec2& terminal, std::span<const Vec2> polygon, WrapSide side,
                        bool into, double tolerance);

/// The walk round the boundary with the polygon on the cable's right (clockwise for Left,
/// counter-clockwise for Right): +1 or -1 per vertex index.
int walkStep(WrapSide side);

/// True when the segment a-b passes through the interior of the convex CCW polygon.
bool segmentCutsPolygon(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon);

}  // namespace cablelab
