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
//   5a, 6a, 6e.             the implicit midpoint rule: which islands take it, rows pull along
//                           the discrete gradient of their lengths over the step and 2-6 run
//                           again, twice (pullAlongDiscreteGradient), each row's work equal to its
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

// 2-6 on the island's rows, again where rows merge or joints lock.
void solveRows(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
               std::span<Vec3> loads, StepStats& stats) {
  for (bool again = true; again;) {
    prepareRows(ws, in, cables, loads);                           // 2-4
    if (ws.ahead.empty() && redirectBlockedRows(ws, in, cables))  // 4b
      prepareRows(ws, in, cables, loads);
    ws.midpoint = takesMidpointRule(ws, in, cables);  // 5a
    targetAndSolveLengths(ws, in, cables, stats);     // 5, 5b, 6, 6d
    for (int pass = 0; pass < 2 && ws.midpoint && pullAlongDiscreteGradient(ws, in, cables);
         ++pass) {  // 6e
      prepareRows(ws, in, cables, loads);
      targetAndSolveLengths(ws, in, cables, stats);
    }
    if (ws.midpoint) balanceMidpointWork(ws, in, cables);  // 6a
    again = mergeSlidingSpans(ws, cables);                 // 6b
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
