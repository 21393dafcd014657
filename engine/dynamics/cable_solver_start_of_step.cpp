// The start-of-step linearisation of the cable solve (cable_solver.cpp, stage 6): Newton's
// shortcut where its remainder bound shows it exact, and the answer where Newton finds none.
#include "engine/dynamics/cable_solver_stages.h"

#include <algorithm>

#include "engine/cable/wrap.h"
#include "engine/dynamics/step_pose.h"

namespace cablelab::cable_stages {

namespace {

// Newton's shortcut. Where every row is a sum of distances between points fixed on bodies (no
// circle, no floor), phi1 = phi0 + h J0 v1 + R with a remainder R that the motion bounds
// (lengthRemainderBound). The start-of-step linearisation is then solved as one LCP, with no
// kinematics at a predicted pose, and kept when R is provably below kLinearTolerance: the end-of-
// step lengths are those Newton would converge to, to that tolerance. A body at rest, or slow
// against its segments' lengths, takes it (the hand holding its box); a fast one takes Newton.
constexpr double kLinearTolerance = 1e-12;  // m
bool linearShortcut = true;

bool pointRowsOnly(const Workspace& ws, std::span<const Cable> cables) {
  for (const Workspace::Row& row : ws.rows) {
    if (row.segment >= 0) return false;
    for (int k = row.first; k <= row.last; ++k)
      for (const WrapPoint& w : cables[row.cable].spanPath(k))
        if (w.radius != 0) return false;
  }
  return true;
}

// J v* for one row at the start of the step along the Jacobians it pulls along (W's): v* on the
// dofs, the prescribed motion elsewhere. A row merged over a capstan constrains its spans'
// plain summed length (the weights are how hard each pulls), as J0 W's rows do.
double startRate(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int r) {
  double rate = 0;
  forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double) {
    for (const auto& e : jacobian) {
      if (const int d = ws.dofs.ofBody[e.body]; d >= 0) {
        rate += e.d.dot(ws.vStar.segment<3>(d));
      } else {
        const BodyState& b = in.bodies[e.body];
        rate += e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
      }
    }
  });
  return rate;
}

}  // namespace

// The LCP on the start-of-step linearisation phi1 = phi0 + h J v1 (ws.lcpSolution): the
// shortcut's, and the answer where Newton on the end-of-step lengths diverges. Its J W is
// positive semidefinite, so its impulses are bounded by the motion they stop.
void solveStartOfStep(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                      bool redundant) {
  const int m = static_cast<int>(ws.rows.size());
  const double h = in.h;
  ws.K = ws.JW0;
  ws.b.resize(m);
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    double goal = ws.target[r];
    if (c.elastic() && row.segment < 0) {  // the implicit spring-damper (lengthTargets)
      const ElasticRow spring = elasticRow(ws, c, row, h);
      ws.K(r, r) += spring.compliance;
      goal = spring.damped;
    }
    ws.b[r] = (ws.phi0[r] - goal) / h + startRate(ws, in, cables, r);
  }
  solveLcp(ws.K, ws.b, ws.lcp, ws.lcpSolution, redundant);
}

// The shortcut's LCP on the start-of-step linearisation; true (ws.P set) if its remainder bound
// holds on every row.
bool solveLinearised(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     bool redundant, StepStats& stats) {
  if (!linearShortcut || ws.midpoint || !pointRowsOnly(ws, cables) ||
      std::find(ws.ahead.begin(), ws.ahead.end(), 1) != ws.ahead.end())
    return false;
  const double h = in.h;
  solveStartOfStep(ws, in, cables, redundant);
  const LcpSolution& sol = ws.lcpSolution;
  timesImpulses(ws, sol.x);
  ws.v1 = ws.vStar - ws.WP;
  // The remainder bound measures from the straight-line motion. A jointed body turns off it
  // (stepPose) by h |v| a / 2 or less (a = h omega): by far less than the tolerance too.
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const BodyState& s = in.bodies[ws.dofs.body[k]];
    BodyState& p = ws.predicted[ws.dofs.body[k]];
    p.position = s.position + h * ws.v1.segment<2>(3 * k);
    p.angle = s.angle + h * ws.v1[3 * k + 2];
    const double off =
        ws.motions[k].kind == StepMotion::Kind::Free ? 0
        : ws.motions[k].kind == StepMotion::Kind::Jointed
            ? 0.5 * h * h * ws.v1.segment<2>(3 * k).norm() * std::abs(ws.v1[3 * k + 2])
            : kLinearTolerance;  // pivoted: its anchor goes back on the pivot
    if (!(off <= 0.1 * kLinearTolerance)) return false;
  }
  for (const Workspace::Row& row : ws.rows)
    for (int k = row.first; k <= row.last; ++k)
      if (!(lengthRemainderBound(cables[row.cable].spanPath(k), in.bodies, ws.predicted) <=
            kLinearTolerance))
        return false;
  ws.P = sol.x;
  stats.solverIterations += sol.iterations;
  stats.residual = std::max(stats.residual, sol.residual);
  ++stats.linearSolves;
  return true;
}

// Rigid rows whose lengths no pose meets (redundant cables with rest lengths that disagree: a
// ring on 40 cables, some 1 or 2 cm short). The start-of-step LCP's targets, each row shortened
// by its Baumgarte share, then ask for a velocity no motion has, and its impulses grow without
// bound (4e12 N s threw the ring to 400 rad/s). Held at their lengths instead (target phi0), the
// rows ask for none: v1 = 0 meets them, so the impulses are bounded by the motion they stop.
// True if some row was let off its correction.
bool holdOverlongRows(Workspace& ws, std::span<const Cable> cables) {
  bool held = false;
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment >= 0 || cables[row.cable].elastic() || !(ws.target[r] < ws.phi0[r])) continue;
    ws.target[r] = ws.phi0[r];
    held = true;
  }
  return held;
}

}  // namespace cablelab::cable_stages

namespace cablelab {

void setLinearShortcut(bool on) {
  cable_stages::linearShortcut = on;
}

}  // namespace cablelab
