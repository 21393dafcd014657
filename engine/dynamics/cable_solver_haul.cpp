// Stage 6d of the cable solve (cable_solver.cpp): rigid cables that a kinematic body hauls out
// against bodies that cannot give way pay out.
#include "engine/dynamics/cable_solver_stages.h"

#include <algorithm>
#include <cmath>

#include "engine/dynamics/step_pose.h"

namespace cablelab::cable_stages {

namespace {

// 6d. Hauled cables. A kinematic body cannot be stopped. Where it hauls a rigid cable out (its
// prescribed motion lengthens the row by haul_r in the sub-step) and the bodies along the cable
// cannot give way (a load already at its pulley, a boom that its stay holds), no tension holds
// the length: the rows are dependent and their targets inconsistent. Newton then leaves rows
// unmet (a load driven through its pulley and the cable metres long) or answers with impulses
// whose work against the kinematic body dwarfs every energy in the island (1e11 N s on a 10 kg
// load, and Box2D's float joints cannot cancel forces that size). Such rows pay out: solved
// again with the targets haulTargets gives them, kept unless that misses the rows by more, and
// applyForces lengthens each cable by its end-of-step stretch (Cable::payOut; World warns).
constexpr double kHaulUnmet = 1e-5;  // m: a row missed by more is not held
constexpr double kHaulWork = 1e3;    // work against the kinematic bodies, in island energies

// haul_r for the rigid cable rows (h J v over the kinematic bodies); true if any is hauled out.
bool hauledRows(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  bool any = false;
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    if (ws.rows[r].segment >= 0 || cables[ws.rows[r].cable].elastic()) continue;
    double rate = 0;
    forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double weight) {
      for (const auto& e : jacobian)
        if (ws.dofs.ofBody[e.body] < 0) {
          const BodyState& b = in.bodies[e.body];
          rate += weight * e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
        }
    });
    ws.haul[r] = std::max(0.0, in.h * rate);
    any |= ws.haul[r] > 0;
  }
  return any;
}

// Whether the impulses do more work against the kinematic bodies (P_r haul_r / h) than
// kHaulWork times what the island's bodies would have moving at the haul speed on top of their
// own.
bool excessiveHaulWork(const Workspace& ws, double h) {
  const double most = ws.haul.maxCoeff();
  double energy = 0;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k)
    if (ws.invM[3 * k] > 0)
      energy += std::pow(most / h + ws.vStar.segment<2>(3 * k).norm(), 2) / ws.invM[3 * k];
  return ws.P.dot(ws.haul) / h > kHaulWork * energy;
}

// Paying out, a hauled row's target is its length error now plus what the kinematic bodies alone
// lengthen it by over the step, measured on the path (the dofs at their start pose, the kinematic
// bodies at their end pose), not h J v: it asks the rest to take back nothing, neither the
// length's curvature over the step nor a length error of before. The rows it depends on (a floor
// holding the load, a stay holding the boom) then agree with it, and no tension squeezes the load
// between the cable and its floor (at 4 sub-steps such a squeeze reached 1e7 N, the rows nearly
// dependent and their targets apart by the curvature).
void haulTargets(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  for (int body : ws.dofs.body) ws.predicted[body] = in.bodies[body];
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    if (!(ws.haul[r] > 0)) continue;
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    double phi = 0;
    for (int k = row.first; k <= row.last; ++k) {
      pathAhead(ws, c, k, ws.predicted);
      phi += c.spanStretch(k) + ws.kin.length - c.spanKinematics(k).length;
    }
    ws.target[r] = std::max(phi, ws.phi0[r] + ws.haul[r]);
  }
}

}  // namespace

void newtonOnLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     StepStats& stats) {
  ws.haul.setZero(static_cast<Eigen::Index>(ws.rows.size()));
  solveLengths(ws, in, cables, stats);
  if (!ws.hauling || !hauledRows(ws, in, cables)) {
    ws.haul.setZero();
    return;
  }
  double unmet = unmetLength(ws, in, cables);
  // A Newton that ran out of iterations misses by what it had left, not because nothing can give
  // way: a box whirled on a rope from a kinematic jib, jerked taut after going slack, missed by
  // 4e-5 m after 3 iterations, and the rope paid out 3.7 cm for good. Newton goes on from where it
  // stopped before the rows pay out.
  if (unmet > kHaulUnmet) {
    const Eigen::VectorXd stopped = ws.P;
    StepStats more;
    if (iterateNewton(ws, in, cables, ws.redundant, more) == Newton::Converged &&
        realisable(ws, in.h)) {
      stats.solverIterations += more.solverIterations;
      unmet = unmetLength(ws, in, cables);
    } else {
      ws.P = stopped;
    }
  }
  if (unmet <= kHaulUnmet && !excessiveHaulWork(ws, in.h)) {
    ws.haul.setZero();
    return;
  }
  // Paying out, the rows the kinematic bodies haul may come slack and the rest stop what they
  // must (a load arriving at its pulley: an inelastic stop). Where Newton's end-of-step geometry
  // is still near the dependent one (its impulses as large as before), the start-of-step LCP,
  // whose J0 W is positive semidefinite, answers.
  ws.unhauledP = ws.P;
  ws.unhauledTarget = ws.target;
  haulTargets(ws, in, cables);
  solveLengths(ws, in, cables, stats);
  if (excessiveHaulWork(ws, in.h)) {
    solveStartOfStep(ws, in, cables, ws.redundant);
    ws.P = ws.lcpSolution.x;
  }
  if (unmetLength(ws, in, cables) > std::max(unmet, kHaulUnmet)) {
    ws.target = ws.unhauledTarget;
    ws.P = ws.unhauledP;
    ws.haul.setZero();
    return;
  }
  // A cable pays out what it is too long at the end of this answer (phi1 is at it): the 1 cm of
  // an 8 cm haul that a load arriving at its pulley could not take up, then the haul itself
  // while the load stays there, and any length error that the dependent rows keep the motion from
  // taking back. Its length then agrees with the rows it depends on, and the next sub-step's
  // tensions are the least that hold the load, not a squeeze between the cable and a floor.
  for (Eigen::Index r = 0; r < ws.haul.size(); ++r) {
    if (!(ws.haul[r] > 0)) continue;
    ws.haul[r] = std::clamp(ws.phi1[r], 0.0, 2 * ws.haul[r] + std::max(0.0, ws.phi0[r]));
  }
}

}  // namespace cablelab::cable_stages
