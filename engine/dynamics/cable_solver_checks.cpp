// The cable solve's checks on an answer (cable_solver.cpp, stage 6): can Box2D move the bodies so,
// does it add energy rigid rows cannot give, how far does it miss the lengths.
#include "engine/dynamics/cable_solver_stages.h"

#include <cmath>

#include "engine/dynamics/box2d_limits.h"

namespace cablelab::cable_stages {

namespace {

// Whether row r pulls on a kinematic body that moves (it hauls the row, stage 6d).
bool pullsOnDriven(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int r) {
  if (!ws.hauling) return false;  // no kinematic body moves this sub-step (predictPrescribed)
  bool driving = false;
  forStartJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double) {
    for (const auto& e : jacobian) driving |= driven(in.bodies[e.body]);
  });
  return driving;
}

}  // namespace

// Whether Box2D can move the bodies as the impulses ws.P say: it moves no body further than
// b2_maxTranslation (2 m) or b2_maxRotation (pi / 2) a step, and an answer that needs more (a
// root of the end-of-step lengths a whole turn of a drum away) is none.
bool realisable(Workspace& ws, double h) {
  timesImpulses(ws, ws.P);
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const Vec3 v1 = ws.vStar.segment<3>(3 * k) - ws.WP.segment<3>(3 * k);
    if (!(h * v1.head<2>().norm() <= kBox2DMaxStepMove && h * std::abs(v1[2]) <= kBox2DMaxStepTurn))
      return false;
  }
  return true;
}

// Whether the impulses ws.P leave an island of rigid rows (cables and floors) with more kinetic
// energy than such rows can give it. They only stop motion: the start-of-step LCP projects v*
// onto what they allow, which takes energy out, and the lengths they put right add what putting
// them right at their rates takes. A root of the end-of-step lengths that needs more is a pose
// the bodies cannot reach from here: a box whose rope is tied off its centre, turning as it
// reached its pulley at 9 m/s, had its tie point swung round to the pulley's far side, and the
// pair gained 190 J of their 470 in one step. Elastic rows store energy and driven bodies do
// work: their islands are not asked.
constexpr double kRigidEnergyAllowance = 0.1;  // of the kinetic energy at v*
bool addsEnergy(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  double correction = 0;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment < 0 && cables[row.cable].elastic()) return false;
    if (pullsOnDriven(ws, in, cables, r)) return false;
    const double rate = (ws.phi0[r] - ws.target[r]) / in.h;
    if (ws.JW0(r, r) > 0) correction += 0.5 * rate * rate / ws.JW0(r, r);
  }
  timesImpulses(ws, ws.P);
  double before = 0, after = 0;
  for (Eigen::Index d = 0; d < ws.vStar.size(); ++d)
    if (ws.invM[d] > 0) {
      const double v1 = ws.vStar[d] - ws.WP[d];
      before += 0.5 * ws.vStar[d] * ws.vStar[d] / ws.invM[d];
      after += 0.5 * v1 * v1 / ws.invM[d];
    }
  return after > (1 + kRigidEnergyAllowance) * before + correction;
}

// How far the rows miss their targets at the end of the step (m): rigid rows too long, floors
// closed past their length. Leaves phi1 at ws.P.
double unmetLength(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  linearise(ws, in, cables);
  double unmet = 0;
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r)
    if (ws.rows[r].segment >= 0 || !cables[ws.rows[r].cable].elastic())
      unmet = std::max(unmet, ws.phi1[r] - ws.target[r]);
  return unmet;
}

// Whether the impulses ws.P leave a rigid row (a cable or a floor) more than kUnsettledLength
// past its target at the end of the step: the start-of-step answer, where Newton found none, is
// then too far off for the step to keep (World tries a shorter one). An island that a driven
// body hauls is solved again after this (stage 6d), and pays out what it cannot hold.
constexpr double kUnsettledLength = 1e-3;  // m
bool missesLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r)
    if (pullsOnDriven(ws, in, cables, r)) return false;
  return unmetLength(ws, in, cables) > kUnsettledLength;
}

}  // namespace cablelab::cable_stages
