// Label placement in screen space (pixels, y down), without GL: each label goes to the first of
// its candidate places, nearest to its anchor first, that overlaps no label placed before it,
// no reserved rectangle (the scale bar, the colour bar, the key), no body and stays inside the
// view, and off the cables' lines (thin strips). Bodies and cables are a soft limit (the
// least-covered place wins when none is clear of them); the other labels, the reserved rectangles
// and the view's edges are hard ones: a label with no place that keeps them is not shown. A label
// placed away from its anchor gets a leader line.
#pragma once

#include <vector>

#include "engine/core/math.h"

namespace cablelab::ui {

struct LabelBox {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool overlaps(const LabelBox& o) const { return overlapArea(o) > 0; }
  double overlapArea(const LabelBox& o) const;
};

struct LabelRequest {
  Vec2 anchor = Vec2::Zero();  ///< px
  Vec2 offset = Vec2::Zero();  ///< preferred top-left corner relative to the anchor (px)
  double width = 0, height = 0;
};

struct LabelPlacement {
  LabelBox box;
  bool leader = false;  ///< placed away from its anchor: draw a line back to it
  bool shown = true;    ///< false: no place kept off the other labels, `reserved` and the edges
};

/// Bodies as convex screen polygons (either winding) that labels keep off.
using LabelObstacle = std::vector<Vec2>;

/// Places `labels` in order inside `view`, off `reserved`; `gap` is the smallest distance (px)
/// kept from the anchor.
std::vector<LabelPlacement> placeLabels(const std::vector<LabelRequest>& labels,
                                        const std::vector<LabelObstacle>& obstacles,
                                        const LabelBox& view, double gap,
                                        const std::vector<LabelBox>& reserved = {});

/// Whether the convex polygon `poly` and `box` overlap (separating axes): a thin strip along a
/// cable that no sample point of the box falls on still counts.
bool crossesConvex(const LabelBox& box, const LabelObstacle& poly);

/// How much of `box` the obstacles cover, 0..1 (a grid of sample points, plus obstacle
/// vertices inside the box, so that a small body under a big label counts; an obstacle that
/// crosses the box between the samples, a cable's strip, counts as one sample).
double obstacleCover(const LabelBox& box, const std::vector<LabelObstacle>& obstacles);

}  // namespace cablelab::ui
