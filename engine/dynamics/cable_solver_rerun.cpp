// The cable solve's stages that change the rows or the joints and run stages 2-6 again
// (cable_solver.cpp): capstans that slide (6b), joint limits the step crosses (6c).
#include "engine/dynamics/cable_solver_stages.h"

#include <algorithm>
#include <cmath>

namespace cablelab::cable_stages {

// 6b. Capstans: where the sticking tensions break T_high <= T_low e^(mu theta), the cable slides
// at that ratio instead (Euler-Eytelwein): the two rows beside the wheel become one, whose
// constraint is their summed length. True if any merged (then stages 2-6 run again).
bool mergeSlidingSpans(Workspace& ws, std::span<const Cable> cables) {
  bool merged = false;
  for (size_t r = 0; r + 1 < ws.rows.size(); ++r) {
    Workspace::Row& a = ws.rows[r];
    const Workspace::Row& b = ws.rows[r + 1];
    if (a.cable != b.cable || a.last + 1 != b.first || a.segment >= 0 || b.segment >= 0) continue;
    const SpanLink& link = cables[a.cable].link(a.last);
    // An elastic cable's spans slide after the step instead (Cable::slideElasticSpans).
    if (link.grip != Grip::Capstan || cables[a.cable].elastic()) continue;
    const double wa = a.weight(ws.rowWeights, a.last), wb = b.weight(ws.rowWeights, b.first);
    const double ta = ws.P[r] * wa, tb = ws.P[r + 1] * wb;
    const double ratio = std::exp(link.mu * std::max(0.0, link.wrapAngle));
    if (std::max(ta, tb) <= ratio * std::min(ta, tb) * (1 + 1e-9)) continue;
    // The merged row's impulse is b's: a's spans pull with ratio (or 1 / ratio) times it.
    const double scale = (ta > tb ? ratio : 1.0 / ratio) * wb / wa;
    const size_t offset = ws.rowWeights.size();
    for (int k = a.first; k <= a.last; ++k)
      ws.rowWeights.push_back(scale * a.weight(ws.rowWeights, k));
    for (int k = b.first; k <= b.last; ++k) ws.rowWeights.push_back(b.weight(ws.rowWeights, k));
    a.weights = offset;
    a.last = b.last;
    ws.rows.erase(ws.rows.begin() + static_cast<std::ptrdiff_t>(r) + 1);
    merged = true;
    --r;  // the merged row may slide on its next capstan too
  }
  return merged;
}

// 6c. Joint limits (joint_limits.h): true if the solved step takes a limited joint past its
// bound, which it then locks (stages 2-6 run again).
bool lockCrossingLimits(Workspace& ws, const CableSolveInput& in) {
  if (std::none_of(ws.jointIndex.begin(), ws.jointIndex.end(),
                   [&](int j) { return in.joints[j].limited; }))
    return false;
  timesImpulses(ws, ws.P);
  ws.vEnd = ws.vStar - ws.WP;
  return ws.limits.lockCrossing(in.joints, ws.jointIndex, in.bodies, ws.dofs.ofBody, ws.vEnd, in.h);
}

}  // namespace cablelab::cable_stages
