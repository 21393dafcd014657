// Overlay lines kept off the view's screen pieces: a drag arrow pulled into a corner, a target
// cross or a label's leader line stops where it would cross the scale bar, the colour bar, the
// key, the notes, the banner or the PAUSED sign, and goes on past them (issue 38: nothing
// drawn over the bars).
//
// Needs: ui/label_layout.h's LabelBox only (no GL).
#pragma once

#include <vector>

#include "ui/label_layout.h"

namespace cablelab::ui {

/// A straight piece in screen space (px).
struct ScreenSegment {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
};

/// The parts of the segment from `a` to `b` (px) outside every box of `keepOff`, in order from
/// `a`; none when the whole segment is inside them.
std::vector<ScreenSegment> partsOutside(const Vec2& a, const Vec2& b,
                                        const std::vector<LabelBox>& keepOff);

}  // namespace cablelab::ui
