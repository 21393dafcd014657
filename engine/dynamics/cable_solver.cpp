// The cable solver's table of contents: solve() runs the stages in order, each in its own file
// (see cable_solver.h for what they solve, docs/model.md for the equations). Per island:
//   1. buildRows            one row per cable span that pulls on a moving body; the dofs
//                           it moves (wheels that grip a cable split it in spans); a floor
//                           row per short segment that may close up (floors.h). The islands,
//                           rows and dofs are kept from the last sub-step while the cables pull
//                           on the same moving bodies (layoutKey)               cable_solver_rows
//   2. predictVelocities    v* (gravity and loads, no cables) and J^T at the start of the step
//   3. inverseMass          W = M'^-1 J^T, M' with the taut cables' geometric stiffness
//   4. projectOntoJoints    W and v* restricted to what Box2D's joints allow: in the joints'
//                           coordinates for trees (joint_tree.h), else the Schur complement
//                           (2-4 together: prepareRows)                      cable_solver_prepare
//   4b. redirectBlockedRows rows that lost their say pull along J ahead     cable_solver_redirect
//   5. lengthTargets        rigid: the end-of-step length; elastic: the implicit spring-damper
//   5b. floorBounces        a body arriving at its floor with restitution leaves it again,
//                           ending its step with no more energy than it began  cable_solver_bounce
//   6. newtonOnLengths      Newton on the end-of-step lengths, one LCP per iteration
//                                                                             cable_solver_newton
//                           one LCP on the start-of-step linearisation where its remainder bound
//                           (lengthRemainderBound) shows it is exact to 1e-12 m, or where
//                           Newton finds no answer                     cable_solver_start_of_step
//                           the checks on an answer (reachable, no energy gained, lengths met)
//                                                                             cable_solver_checks
//   5a, 6a, 6e.             the implicit midpoint rule: which islands take it (elastic ones with
//                           stage 3's geometric stiffness too, without it), rows pull along
//                           the discrete gradient of their lengths over the step and 2-6 run
//                           again, twice (pullAlongDiscreteGradient; also the main solve's
//                           islands of one-span elastic rows), each row's work equal to its
//                           cable's energy change (balanceMidpointWork)  cable_solver_midpoint
//   6b. mergeSlidingSpans   capstans past e^(mu theta): merge their spans (elastic ones each
//                           a spring of its own, elasticRow), run 2-6 again;
//                           those the rope slid over in the last sub-step are merged from the
//                           start (mergeLastSliding) while it still slides (slidesAsMerged)
//   6c. lockCrossingLimits  a limited joint the step takes past its bound: lock it at the
//                           rate that reaches the bound (joint_limits.h), run 2-6 again
//                                                                              cable_solver_rerun
//   6d. (newtonOnLengths)   rigid cables a kinematic body hauls out against bodies that cannot
//                           give way: solve again with them paying out (Cable::payOut)
//                                                                               cable_solver_haul
//   7. applyForces          the force that gives the solved end-of-step velocity, and the
//                           jointed bodies' end poses (CableSolveInput::placements)
//                                                                             cable_solver_forces
// The workspace the stages share: cable_solver_stages.h.
#include "engine/dynamics/cable_solver.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/dynamics/cable_solver_stages.h"

namespace cablelab {

namespace cable_stages {
namespace {

// 5, 5b, 6: the length targets, then Newton on the end-of-step lengths; where a floor may bounce,
// a first solve with it left free, then the bounce (cable_solver_bounce.cpp).
void targetAndSolveLengths(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                           StepStats& stats) {
  lengthTargets(ws, in.h, in.share, cables);
  if (floorBounces(ws, in, cables))
    solveBouncing(ws, in, cables, stats);
  else
    newtonOnLengths(ws, in, cables, stats);
}

// Whether every cable row of the island is elastic (floor rows aside).
bool everyCableRowElastic(const Workspace& ws, std::span<const Cable> cables) {
  return std::all_of(ws.rows.begin(), ws.rows.end(), [&](const Workspace::Row& row) {
    return row.segment >= 0 || cables[row.cable].elastic();
  });
}

// 5a on an island of elastic rows that stage 3 gave geometric stiffness (h^2 T / (m L) over
// 0.05): the midpoint rule without the stiffness (its Newton follows the rope's turn over the
// step). Left to the main solve, its backward-Euler spring (omega h up to 2) took up to 1.5 times
// a caught weight's largest kinetic energy in a step (docs/knocks.md, "Elastic ropes pulled
// hard"). The bound on omega h is asked again with W = M^-1 J^T; where it fails, the stiffness
// and the main solve come back.
void leaveOutGeometricStiffness(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                                std::span<Vec3> loads) {
  ws.stiffnessLeftOut = true;
  prepareRows(ws, in, cables, loads);
  ws.midpoint = takesMidpointRule(ws, in, cables);
  if (ws.midpoint) return;
  ws.stiffnessLeftOut = false;
  prepareRows(ws, in, cables, loads);
}

// 6e also for the main solve's islands of elastic rows, each one span: pulled along J at the
// start of the step, a rope whose short end segment swings round fast lengthens by about
// (v h)^2 / (2 L) more than J says, and the spring gave the bodies the work of the length J
// predicted: up to 2.6% of the energy scale in a step (a bob 4 cm past the corner of the polygon
// its rope wraps, in a cut the main solve took as the bob touched the hull). Along the discrete
// gradient the row's work is its length change, and the backward-Euler spring can only take
// energy (docs/knocks.md, "Pulled along the turn").
bool pullsAlongDiscreteGradient(const Workspace& ws, std::span<const Cable> cables) {
  if (ws.midpoint) return true;
  return std::all_of(ws.rows.begin(), ws.rows.end(), [&](const Workspace::Row& row) {
    return row.segment >= 0 || (cables[row.cable].elastic() && row.first == row.last);
  });
}

// Whether the island has a floor row: under the midpoint rule a floor that stops a body within
// the step sets v1 = 2 (x1 - x0) / h - v0, throwing it back (elastic Atwoods gained up to 61% of
// their scale), and a resting one may fold the rope's length at its point pulley; such a step is
// judged once solved (judgeFloorOnMidpoint), a gain solved again with the backward-Euler spring
// (docs/floors.md, "A resting light side").
bool hasFloorRow(const Workspace& ws) {
  return std::any_of(ws.rows.begin(), ws.rows.end(),
                     [](const Workspace::Row& row) { return row.segment >= 0; });
}

// 5, 5b, 6 again with the backward-Euler spring: a midpoint step with a floor row (hasFloorRow),
// or whose knock gained (midpointKnockGains).
// `again`: stages 2-4 run again (the knock's start velocities and stage 6e's rows undone).
void solveWithoutMidpointRule(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                              std::span<Vec3> loads, StepStats& stats, bool again) {
  ws.midpoint = false;
  ws.knockedOnMidpoint = false;
  if (ws.stiffnessLeftOut || again) {
    ws.stiffnessLeftOut = false;
    prepareRows(ws, in, cables, loads);
  }
  targetAndSolveLengths(ws, in, cables, stats);
}

// 6e: the rows pull along the discrete gradient of their lengths over the step, twice.
void pullAlongTheStep(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                      std::span<Vec3> loads, StepStats& stats) {
  const bool gradient = pullsAlongDiscreteGradient(ws, cables);
  for (int pass = 0; pass < 2 && gradient && pullAlongDiscreteGradient(ws, in, cables); ++pass) {
    prepareRows(ws, in, cables, loads);
    targetAndSolveLengths(ws, in, cables, stats);
  }
}

// 2-6 on the island's rows, again where rows merge or joints lock.
void solveRows(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
               std::span<Vec3> loads, StepStats& stats) {
  static thread_local std::pair<std::vector<char>, std::vector<std::vector<BodyJacobian>>>
      aheadBeforeKnock;  // scratch: a knocked midpoint step's rows before stage 6e
  for (bool again = true; again;) {
    ws.stiffnessLeftOut = false;
    prepareRows(ws, in, cables, loads);                           // 2-4
    if (ws.ahead.empty() && redirectBlockedRows(ws, in, cables))  // 4b
      prepareRows(ws, in, cables, loads);
    ws.midpoint = takesMidpointRule(ws, in, cables);  // 5a
    if (ws.midpoint && ws.stiff && everyCableRowElastic(ws, cables))
      leaveOutGeometricStiffness(ws, in, cables, loads);
    else if (ws.stiff)
      ws.midpoint = false;
    ws.knockedOnMidpoint = false;
    targetAndSolveLengths(ws, in, cables, stats);  // 5, 5b, 6, 6d
    if (ws.midpoint && hasFloorRow(ws) && !ws.knockedOnMidpoint)
      judgeFloorOnMidpoint(ws, in, cables);  // a gain goes to the backward-Euler spring below
    if (ws.knockedOnMidpoint) aheadBeforeKnock = {ws.ahead, ws.aheadJacobian};
    pullAlongTheStep(ws, in, cables, loads, stats);        // 6e
    if (ws.midpoint) balanceMidpointWork(ws, in, cables);  // 6a
    if (ws.knockedOnMidpoint && midpointKnockGains(ws, in, cables)) {
      ws.ahead = aheadBeforeKnock.first;
      ws.aheadJacobian = aheadBeforeKnock.second;
      solveWithoutMidpointRule(ws, in, cables, loads, stats, true);
      pullAlongTheStep(ws, in, cables, loads, stats);
    }
    again = mergeSlidingSpans(ws, cables);  // 6b
    if (again) {
      ws.ahead.clear();  // the rows changed: measure them again
    } else {
      again = lockCrossingLimits(ws, in);  // 6c
    }
  }
}

void solve(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables, std::span<Vec3> loads,
           StepStats& stats) {
  const int islands = findIslands(ws, in, cables);  // 1
  if (islands == 0) return;
  if (ws.dofs.ofBody.size() != in.bodies.size()) ws.dofs.reset(in.bodies.size());
  if (ws.warm.size() != cables.size()) {
    ws.warm.assign(cables.size(), {});
    ws.floorWarm.assign(cables.size(), {});
  }
  predictPrescribed(ws, in);
  for (int island = 0; island < islands; ++island) {
    // Big islands take the sparse path where it applies (sparse_island.h says which).
    if (ws.sparse.solve(in, cables, ws.islandRows[island], ws.islandJoints[island], ws.predicted,
                        loads, stats))
      continue;
    for (bool premerged = true;;) {
      buildRows(ws, in, cables, island);  // 1
      ws.ahead.clear();
      ws.limits.free(ws.jointIndex, static_cast<int>(in.joints.size()));
      premerged = premerged && mergeLastSliding(ws, cables);  // 6b, as last sub-step
      solveRows(ws, in, cables, loads, stats);
      if (!premerged || slidesAsMerged(ws, cables, in.h)) break;
      premerged = false;
    }
    applyForces(ws, in, cables, loads);  // 7
  }
  ws.dofs.clear();
}

}  // namespace
}  // namespace cable_stages

CableSolver::CableSolver(std::vector<double> restitution)
    : ws_(std::make_unique<CableSolverWorkspace>()) {
  ws_->restitution = std::move(restitution);
}
CableSolver::~CableSolver() = default;

void CableSolver::solve(const CableSolveInput& in, std::span<Cable> cables, std::span<Vec3> loads,
                        StepStats& stats) {
  cable_stages::solve(*ws_, in, cables, loads, stats);
}

}  // namespace cablelab
