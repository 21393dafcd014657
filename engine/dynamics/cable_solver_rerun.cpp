// The cable solve's stages that change the rows or the joints and run stages 2-6 again
// (cable_solver.cpp): capstans that slide (6b), joint limits the step crosses (6c).
#include "engine/dynamics/cable_solver_stages.h"

#include <algorithm>
#include <cmath>

namespace cablelab::cable_stages {
namespace {

// A capstan between rows r and r + 1 (consecutive spans of one cable), or null. An elastic
// cable's merged row keeps its spans' material in sum, each span its own spring (elasticRow).
const SpanLink* slidingCapstan(const Workspace& ws, std::span<const Cable> cables, size_t r) {
  const Workspace::Row &a = ws.rows[r], &b = ws.rows[r + 1];
  if (a.cable != b.cable || a.last + 1 != b.first || a.segment >= 0 || b.segment >= 0)
    return nullptr;
  const SpanLink& link = cables[a.cable].link(a.last);
  if (link.grip != Grip::Capstan) return nullptr;
  return &link;
}

// Rows r and r + 1 become one, sliding towards r's side if firstHigh (Euler-Eytelwein: the high
// side pulls with e^(mu theta) times the low side). The merged row's impulse is r + 1's.
void mergeRows(Workspace& ws, const SpanLink& link, size_t r, bool firstHigh) {
  Workspace::Row& a = ws.rows[r];
  const Workspace::Row& b = ws.rows[r + 1];
  const double ratio = std::exp(link.mu * std::max(0.0, link.wrapAngle));
  const double wa = a.weight(ws.rowWeights, a.last), wb = b.weight(ws.rowWeights, b.first);
  const double scale = (firstHigh ? ratio : 1.0 / ratio) * wb / wa;
  const size_t offset = ws.rowWeights.size();
  for (int k = a.first; k <= a.last; ++k)
    ws.rowWeights.push_back(scale * a.weight(ws.rowWeights, k));
  for (int k = b.first; k <= b.last; ++k) ws.rowWeights.push_back(b.weight(ws.rowWeights, k));
  a.weights = offset;
  a.last = b.last;
  ws.rows.erase(ws.rows.begin() + static_cast<std::ptrdiff_t>(r) + 1);
}

// The rate at which rope crosses the capstan after span `link` of row r into the spans before
// it, at the end-of-step velocities ws.vEnd (start-of-step Jacobians). On an elastic cable what
// crosses is material: the spans' length rate less their stretch rate (springStretchAtEnd).
double slipRate(Workspace& ws, std::span<const Cable> cables, size_t r, int link, double h) {
  const Workspace::Row& row = ws.rows[r];
  const Cable& c = cables[row.cable];
  double rate = 0;
  for (int k = row.first; k <= link; ++k) {
    for (const BodyJacobian& e : c.spanKinematics(k).jacobian) {
      const int dof = ws.dofs.ofBody[e.body];
      if (dof >= 0) rate += e.d.dot(ws.vEnd.segment<3>(dof));
    }
    if (c.elastic()) {
      const double impulse = row.weight(ws.rowWeights, k) * ws.P[r];
      rate -= (springStretchAtEnd(c, k, impulse, h) - c.spanStretch(k)) / h;
    }
  }
  return rate;
}

}  // namespace

// 6b. Capstans: where the sticking tensions break T_high <= T_low e^(mu theta), the cable slides
// at that ratio instead (Euler-Eytelwein): the two rows beside the wheel become one, whose
// constraint is their summed length (an elastic cable's: their summed stretch, elasticRow). True
// if any merged (then stages 2-6 run again).
bool mergeSlidingSpans(Workspace& ws, std::span<const Cable> cables) {
  bool merged = false;
  for (size_t r = 0; r + 1 < ws.rows.size(); ++r) {
    const SpanLink* link = slidingCapstan(ws, cables, r);
    if (!link) continue;
    const Workspace::Row &a = ws.rows[r], &b = ws.rows[r + 1];
    const double ta = ws.P[r] * a.weight(ws.rowWeights, a.last);
    const double tb = ws.P[r + 1] * b.weight(ws.rowWeights, b.first);
    const double ratio = std::exp(link->mu * std::max(0.0, link->wrapAngle));
    if (std::max(ta, tb) <= ratio * std::min(ta, tb) * (1 + 1e-9)) continue;
    mergeRows(ws, *link, r, ta > tb);
    merged = true;
    --r;  // the merged row may slide on its next capstan too
  }
  return merged;
}

// 6b, before the solve: capstans the cable slid over in the last sub-step (its span tensions at
// the ratio e^(mu theta), to a rounding of the wrap angle's change) are merged from the start, so
// that a rope that keeps sliding is solved once, not stuck first and then merged (the capstan
// at m_load=30 slides onto its hold weight at the drum; stuck, its rows are redundant).
// slidesAsMerged checks the guess after the solve. True if any merged.
bool mergeLastSliding(Workspace& ws, std::span<const Cable> cables) {
  bool merged = false;
  for (size_t r = 0; r + 1 < ws.rows.size(); ++r) {
    const SpanLink* link = slidingCapstan(ws, cables, r);
    if (!link) continue;
    const Cable& c = cables[ws.rows[r].cable];
    const double ta = c.spanTension(ws.rows[r].last), tb = c.spanTension(ws.rows[r + 1].first);
    const double ratio = std::exp(link->mu * std::max(0.0, link->wrapAngle));
    if (!(std::min(ta, tb) > 0) || std::max(ta, tb) < 0.99 * ratio * std::min(ta, tb)) continue;
    mergeRows(ws, *link, r, ta > tb);
    merged = true;
    --r;
  }
  return merged;
}

// Whether the rope slides over each merged capstan the way its weights assume, or rests on it.
// Otherwise friction stopped it within the step, and the rows are solved apart (stage 6b).
bool slidesAsMerged(Workspace& ws, std::span<const Cable> cables, double h) {
  timesImpulses(ws, ws.P);
  ws.vEnd = ws.vStar - ws.WP;
  constexpr double kSlipTolerance = 1e-8;  // m/s: rope at rest on the capstan
  for (size_t r = 0; r < ws.rows.size(); ++r)
    for (int k = ws.rows[r].first; k < ws.rows[r].last; ++k) {
      const Workspace::Row& row = ws.rows[r];
      const bool firstHigh = row.weight(ws.rowWeights, k) > row.weight(ws.rowWeights, k + 1);
      const double slip = slipRate(ws, cables, r, k, h);
      if ((firstHigh ? slip : -slip) < -kSlipTolerance) return false;
    }
  return true;
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
