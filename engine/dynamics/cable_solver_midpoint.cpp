// The implicit midpoint rule's stages of the cable solve (cable_solver.cpp): which islands take it
// (5a), its rows' discrete gradient, the energy balance of its impulses (6a) and the discrete
// gradient of the lengths its rows pull along (6e).
#include "engine/dynamics/cable_solver_stages.h"

#include <cmath>

#include "engine/dynamics/step_pose.h"

namespace cablelab::cable_stages {

namespace {

// A rigid row under the midpoint rule (stage 5a). Box2D's symplectic Euler swings the measured
// energy of a rope over a spinning pulley by about omega h / 2 (the built-in hexagon on its pivot:
// 3.2% of its largest kinetic energy at 1 sub-step, a square 11%); the midpoint rule holds it to
// 0.5% and 2.9%. Only where the rest of the step is exact under that rule too:
// - every joint is a revolute one without limits at the centre of mass of a body it hangs from
//   one that does not move (a pulley on its axle). Gravity's torque about an off-centre pivot is
//   taken at the start pose, and with q1 = q0 + h (v0 + v1) / 2 a start-pose force gains energy
//   every swing (a pendulum carrying an eyelet: +64% in a minute); without gravity a puck caught
//   by a rope on an arm pivoted off its centre kept 86% of the energy that Box2D's integration
//   kept to 1%, and a rope from a carriage on a rail stretched 3.5 mm (1e-6 m);
// - no circle, drum or kinematic body on the path, one span;
// - some pulley of the cable on a moving body (else Box2D's own integration, as the midpoint
//   solver leaves straight cables over fixed pulleys).
// The island's part of the conditions (its joints), then the cable's.
bool jointsAreAxles(const Workspace& ws, const CableSolveInput& in) {
  if (ws.jointIndex.empty()) return false;
  for (int j : ws.jointIndex) {
    const JointFrame& f = in.joints[j];
    const bool movesA = f.bodyA >= 0 && moves(in.bodies[f.bodyA]);
    const bool movesB = f.bodyB >= 0 && moves(in.bodies[f.bodyB]);
    if (f.limited || f.kind != JointDef::Kind::Revolute || (movesA && movesB)) return false;
    const Vec2 centre = in.bodies[movesA ? f.bodyA : f.bodyB].position;
    if ((f.anchor - centre).squaredNorm() > 1e-18) return false;
  }
  return true;
}
bool rigidRowTakesMidpointRule(const CableSolveInput& in, const Cable& c) {
  if (c.spanCount() != 1) return false;
  for (const WrapPoint& w : c.path())
    if (w.radius != 0 || (w.body >= 0 && driven(in.bodies[w.body]))) return false;
  for (int j = 0; j < c.pulleyCount(); ++j)
    if (c.pulleyBody(j) >= 0 && moves(in.bodies[c.pulleyBody(j)])) return true;
  return false;
}

// A floor row the midpoint rule keeps (as a plain floor), knocked (floorKnock) or resting:
// along an elastic rope's segment between two points (a body's anchor, a point pulley). Ruled out,
// an elastic Atwood's light side near its point pulley took the backward-Euler spring, which at
// omega h = 1 lost 43% of the knock's kinetic energy in the step (docs/floors.md, "Bouncing off a
// pulley"). A step whose floor pushes is judged once solved (judgeFloorOnMidpoint).
bool pointFloorOfElasticRope(const Workspace::Row& row, const Cable& c) {
  return row.segment >= 0 && !row.rim && c.elastic() && c.path()[row.segment].radius == 0 &&
         c.path()[row.segment + 1].radius == 0;
}

constexpr double kRestingSpeed = 0.1;  // m/s: a floor's bodies slower than this rest on it

// Whether every body along the floor row's segment moves slower than kRestingSpeed: a light side
// sweeping past its pulley without a knock gained up to 15% of a busy scene's scale in a step
// under the midpoint rule, where a resting one keeps its energy (docs/floors.md).
bool floorRests(const CableSolveInput& in, const Cable& c, const Workspace::Row& row) {
  for (int p = row.segment; p <= row.segment + 1; ++p) {
    const int body = c.path()[p].body;
    if (body >= 0 && in.bodies[body].velocity.norm() >= kRestingSpeed) return false;
  }
  return true;
}

constexpr int kBalancePasses = 4;
// The main solve pulls along the turn only where a row's length misses J's by more (m).
constexpr double kTurnedLength = 1e-11;

}  // namespace

// 5a. Undamped elastic cables on jointed (or touching-free) bodies: the backward-Euler spring of
// stage 5 damps them (an arm on a pivot pulled by a k = 200 N/m cable lost 90% of its energy in
// 1 s). Where every row of the island is such a cable, no body touches, and each row's axial
// mode is resolved (omega h <= 2, omega^2 = k J0 W), the island takes the implicit midpoint rule
// instead: q1 = q0 + h (v0 + v1) / 2, the spring pulling with its energy's discrete gradient
// (midpointSpringRows: k (phi0 + phi1) / 2 while taut), Box2D moving the bodies with
// (v0 + v1) / 2 and World adding the rest after its step (kicks). The joints allow v0 and v1
// alike, so they allow every velocity Box2D sees. The midpoint solver's rule (docs/cables.md,
// "Energy"), here with the joint projection of stages 2-4. An island with stage 3's geometric
// stiffness is decided by the caller (leaveOutGeometricStiffness, cable_solver.cpp).
bool takesMidpointRule(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  if (in.kicks.empty() || ws.rows.empty()) return false;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k)
    if (!in.touching.empty() && in.touching[ws.dofs.body[k]]) return false;
  int axles = -1;  // jointsAreAxles, asked once, where a rigid row needs it
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    // A point floor of an elastic rope, knocked or resting: the step is judged once solved
    // (judgeFloorOnMidpoint, docs/floors.md, "A resting light side").
    if (double phi = 0;
        pointFloorOfElasticRope(row, c) &&
        (floorKnock(ws, in, cables, static_cast<int>(r), phi) > 0 || floorRests(in, c, row)))
      continue;
    if (row.segment >= 0 || row.first != row.last) return false;
    if (!c.elastic()) {
      // A row stage 4b redirected (a point joining fast) takes the rule too: stage 6e's discrete
      // gradient gives the joining point its share over the step exactly, where 4b's half share
      // guesses at it. Left to the main solve, the built-in hexagon at 1 sub-step gained 7e-4 J
      // at each of its vertices' joins (at 4 rad/s, 0.1 J a minute of its 2.5 J).
      if (axles < 0) axles = jointsAreAxles(ws, in);
      if (!axles || !rigidRowTakesMidpointRule(in, c)) return false;
      continue;
    }
    if (c.damping() != 0 || c.spanCount() > 1) return false;  // (elastic spans: a stiffness each)
    const double say = rowSay(ws, in.bodies, cables, static_cast<int>(r));
    if (!(c.stiffness() * say * in.h * in.h <= 4)) return false;
  }
  return true;
}

// The midpoint rule's rows at Newton's iterate (phi1 at q0 + h (v0 + v1) / 2): the cable pulls
// with the discrete gradient of its energy V = k/2 max(0, phi)^2, P = h g, g = (V(phi1) -
// V(phi0)) / (phi1 - phi0) (k (phi0 + phi1) / 2 while taut throughout; across a slack-taut
// switch the exact quotient, or the switch gains or loses energy). With s = dg/dphi1 and
// dphi1/dP = -(h/2) J1 W, Newton's row is (J1 W + 2 / (h^2 s)) P = J1 W P_k + 2 g / (h s).
void midpointSpringRows(Workspace& ws, std::span<const Cable> cables, double h) {
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    if (!cables[ws.rows[r].cable].elastic() || ws.rows[r].segment >= 0) continue;
    const double k = cables[ws.rows[r].cable].stiffness();
    const double p0 = ws.phi0[r], p1 = ws.phi1[r], d = p1 - p0;
    double g, s;
    if ((p0 >= 0 && p1 >= 0) || (p0 <= 0 && p1 <= 0) || std::abs(d) < 1e-300) {
      g = 0.5 * k * (p0 + p1), s = 0.5 * k;  // slack throughout: g < 0, the LCP leaves it slack
    } else if (p1 > 0) {                     // comes taut
      g = 0.5 * k * p1 * p1 / d, s = 0.5 * k * p1 * (p1 - 2 * p0) / (d * d);
    } else {  // goes slack
      g = -0.5 * k * p0 * p0 / d, s = 0.5 * k * p0 * p0 / (d * d);
    }
    s = std::max(s, 1e-12 * k);
    ws.compliance[r] = 2 / (h * h * s);
    ws.pull[r] = 2 * g / s;
  }
}

// 6a. The midpoint rule's energy balance. Row r's impulse does work P_r J_r (v0 + v1) / 2 on the
// bodies (J_r the Jacobian it pulls along; the joints' reactions do none), and the cable's energy
// changes by V(phi1) - V(phi0). Newton's discrete gradient makes the two equal where phi1 -
// phi0 = h J_r (v0 + v1) / 2; the length's curvature and a jointed body's turn (stepPose) leave
// a second-order difference, which over many swings adds up: an arm on a pivot with an undamped
// spring, its joint keeping its energy (joint_energy.h), gained 2.3 times its energy in 60 s at
// 60 Hz. Each pulling row's impulse is scaled until the two match, where the factor is within
// 0.5..2 (a few passes: the scaling moves the end pose a little).
void balanceMidpointWork(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  for (int pass = 0; pass < kBalancePasses; ++pass) {
    linearise(ws, in, cables);  // phi1 and v1 at these impulses
    double worst = 0;
    for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
      if (!(ws.P[r] > 0) || ws.rows[r].segment >= 0) continue;
      double rate = 0;  // J_r (v0 + v1) / 2
      forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double) {
        for (const auto& e : jacobian)
          if (const int d = ws.dofs.ofBody[e.body]; d >= 0)
            rate += 0.5 * e.d.dot(ws.v0.segment<3>(d) + ws.v1.segment<3>(d));
      });
      const double k = cables[ws.rows[r].cable].stiffness();
      auto energy = [&](double phi) { return phi > 0 ? 0.5 * k * phi * phi : 0.0; };
      const double scale = (energy(ws.phi1[r]) - energy(ws.phi0[r])) / (ws.P[r] * rate);
      if (!(scale > 0.5 && scale < 2)) continue;
      ws.P[r] *= scale;
      worst = std::max(worst, std::abs(scale - 1));
    }
    if (worst < 1e-9) return;
  }
}

// What stage 6a left unbalanced: the energy the elastic rows' impulses give the island beyond
// their cables' energy change, sum of V(phi1) - V(phi0) - P_r J_r (v0 + v1) / 2, at the impulses
// now (J (v0 + v1) / 2 and phi1 taken again). Where a row's factor fell outside 0.5..2 (the band's
// length rate small beside the turn's share of it: a square pendulum's corner in an elastic band
// near the bottom of its swing, 0.3 mJ a step of its 3 J) it is all that row's mismatch.
double midpointWorkLeft(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  linearise(ws, in, cables);
  double left = 0;
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    const Cable& c = cables[ws.rows[r].cable];
    if (!(ws.P[r] > 0) || !c.elastic() || ws.rows[r].segment >= 0) continue;
    double rate = 0;
    forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double) {
      for (const auto& e : jacobian)
        if (const int d = ws.dofs.ofBody[e.body]; d >= 0)
          rate += 0.5 * e.d.dot(ws.v0.segment<3>(d) + ws.v1.segment<3>(d));
    });
    const double k = c.stiffness();
    auto energy = [&](double phi) { return phi > 0 ? 0.5 * k * phi * phi : 0.0; };
    left += energy(ws.phi1[r]) - energy(ws.phi0[r]) - ws.P[r] * rate;
  }
  return left;
}

namespace {

// Whether a pulling row's length over the step, from the solve's end pose, differs from what the
// Jacobian it pulled along predicts by more than kTurnedLength: only then does the main solve
// pull along the discrete gradient (stage 6e). Its error in work is that difference times the
// tension; a rope that barely turns over the step (a hand holding its box) is left as solved.
bool turnsOffItsPull(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    if (ws.rows[r].segment >= 0 || !(ws.P[r] > 0)) continue;
    double predicted = 0;  // h J v1
    forForceJacobians(ws, in.bodies, cables, r, [&](const auto& jacobian, double weight) {
      for (const auto& e : jacobian)
        if (const int d = ws.dofs.ofBody[e.body]; d >= 0)
          predicted += weight * in.h * e.d.dot(ws.v1.segment<3>(d));
    });
    if (std::abs(ws.phi1[r] - ws.phi0[r] - predicted) > kTurnedLength) return true;
  }
  return false;
}

}  // namespace

// 6e. Under the midpoint rule each pulling row pulls along the discrete gradient G of its length
// between the start of the step and the end the solve found (lengthDiscreteGradient: G (q1 - q0)
// = length(q1) - length(q0) exactly, a turning body's points moved along their chords), then the
// step is solved again (stages 2-6). A rigid row that holds its length then does no work, and an
// elastic row's work is its energy change. Along the start-of-step J a rigid row's work added up
// on a turning path (the hexagon on its pivot gained 47% of its largest kinetic energy in a
// minute); along J at the midpoint pose it still missed the length change by the third order in
// the turn, always the same way after a wrap change: the built-in hexagon spun at 4 rad/s lost
// 0.68% of its energy scale a minute at 2 sub-steps (6.1% in ten minutes), elastic ropes over a
// spinning polygon lost what stage 6a's factors could not balance. The solve calls this twice: G
// is taken once more at the end the first re-solve found (from the first solve's end alone, that
// hexagon still lost 1.2% in ten minutes). Rows the solve left slack keep what they pulled along.
// True if any row changed (stages 2-6 run again).
bool pullAlongDiscreteGradient(Workspace& ws, const CableSolveInput& in,
                               std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  timesImpulses(ws, ws.P);
  ws.v1 = ws.vStar - ws.WP;
  if (!ws.midpoint && !turnsOffItsPull(ws, in, cables)) return false;
  if (static_cast<int>(ws.ahead.size()) != m) ws.ahead.assign(m, 0);
  ws.aheadJacobian.resize(m);
  ws.free.assign(ws.predicted.begin(), ws.predicted.end());
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const int b = ws.dofs.body[k];
    stepPose(in.bodies[b], movedWith(ws, k, ws.v1.segment<3>(3 * k)), in.h, ws.motions[k],
             ws.free[b]);
  }
  bool any = false;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    if (row.segment >= 0 || !(ws.P[r] > 0)) continue;
    pathAhead(ws, cables[row.cable], row.first, ws.free);
    lengthDiscreteGradient(ws.path, in.bodies, ws.free, ws.aheadJacobian[r]);
    ws.ahead[r] = 1;
    any = true;
  }
  return any;
}

}  // namespace cablelab::cable_stages
