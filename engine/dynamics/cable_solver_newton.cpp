// Stages 5 and 6 of the cable solve (cable_solver.cpp): the length targets, and Newton on the
// end-of-step lengths with its warm start and its fallbacks.
#include "engine/dynamics/cable_solver_stages.h"

#include <algorithm>
#include <limits>

#include "engine/dynamics/floors.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/newton_stop.h"
#include "engine/dynamics/step_pose.h"

namespace cablelab::cable_stages {

namespace {

constexpr int kNewtonIterations = 3;  // on the end-of-step lengths; geometry is nearly linear
// With redundant rows Newton runs on J0 W (a chord method): it converges linearly, not
// quadratically, and a fast catch needs more steps (a puck at 50 m/s: 29 mm stretch after 3).
constexpr int kChordIterations = 12;

bool keepImpulses = true;  // setKeptImpulses

// Warm start: a cable's tension changes little from one sub-step to the next, so Newton starts
// from the impulses of the last solve when it had the same h and nothing has set the tension
// since (after a step cut at an event the impulse is not force times h: a length correction is
// m dv whatever h). A floor row starts from its impulse of that solve, on the segment between
// the same two points, else at 0. True if any row starts away from 0.
bool warmStart(Workspace& ws, double h, std::span<const Cable> cables) {
  const int m = static_cast<int>(ws.rows.size());
  ws.P.setZero(m);
  bool warm = false;
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    const Workspace::WarmStart& last = ws.warm[row.cable];
    if (last.h != h || last.tension != c.tension() || last.spans != c.spanCount()) continue;
    if (row.segment >= 0 && keepImpulses) {
      const Workspace::FloorImpulse here = floorImpulse(c, row, 0);
      for (const Workspace::FloorImpulse& f : ws.floorWarm[row.cable])
        if (f.fromPulley == here.fromPulley && f.fromVertex == here.fromVertex &&
            f.toPulley == here.toPulley && f.toVertex == here.toVertex && f.rim == here.rim)
          ws.P[r] = f.impulse;
    } else if (row.segment < 0) {
      ws.P[r] = std::max(0.0, c.spanTension(row.first) / row.weight(ws.rowWeights, row.first)) * h;
    }
    warm |= ws.P[r] > 0;
  }
  return warm;
}

// Whether the warm start ws.P already answers the step: at its end-of-step pose every row that
// pulls meets its target and every other row asks for no pull, each to Newton's own tolerance
// (newtonSettled's on a first step), so that the next iteration's LCP would give P back. A body
// resting at its pulley is held by the same impulses step after step (a tackle's block at its
// top sheave: three chord iterations, each an LCP over the redundant floors, found them again;
// docs/floors.md, "Resting at a pulley"). Only for redundant rows, whose step Newton measures by
// the rows' rates over their diagonals (impulseChange), which the unmet rates give without a
// solve; elsewhere it measures the impulses themselves, which take the solve (a massless
// wheel's huge diagonal hid a 6% change of its rope's tension). Leaves phi1 at ws.P.
bool lastImpulsesHold(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  // (The midpoint rule's right-hand side moves with phi1; elastic rows make the LCP definite.)
  if (!keepImpulses || !ws.redundant || ws.midpoint || !(ws.compliance.array() == 0).all())
    return false;
  linearise(ws, in, cables);
  const double tolerance = 1e-9 * (1e-9 + ws.P.lpNorm<Eigen::Infinity>());
  // The minimum-norm LCP's answer is its own fixed point with each pulling row short by its
  // compliance times its impulse (tension_solver.h).
  const double bias = minimumNormCompliance(ws.JW0.diagonal());
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    const double w = -(ws.phi1[r] - ws.target[r]) / in.h;  // K P - b of iterateNewton's LCP (m/s)
    const double allowed = tolerance * ws.JW0(r, r);
    if (ws.P[r] > 0 ? !(std::abs(w + bias * ws.P[r]) <= allowed) : !(w >= -allowed)) return false;
  }
  return true;
}

}  // namespace

Workspace::FloorImpulse floorImpulse(const Cable& c, const Workspace::Row& row, double impulse) {
  const WrapPoint &from = c.path()[row.segment], &to = c.path()[row.segment + 1];
  return {from.pulley, from.vertex, to.pulley, to.vertex, row.rim, impulse};
}

// 5. Position-level targets. Rigid: length at the end of the step = now (the error below the
// slop is float rounding: fixing it would amplify it by 1/h^2), a slack cable may come taut, an
// over-long one is shortened by a share of the excess per nominal sub-step (a step cut at an
// event fixes its share of that: fixing it all would ask for a velocity of error / h). Elastic: T =
// k phi1 + b (phi1 - phi0)/h.
void lengthTargets(Workspace& ws, double h, double share, std::span<const Cable> cables) {
  // Floors are rigid rows on kFloorLength - |segment|: they only ever push.
  const double beta = kBaumgarte * share;
  const int m = static_cast<int>(ws.rows.size());
  ws.target.resize(m);
  ws.compliance.setZero(m);
  ws.damped.setZero(m);
  ws.pull.setZero(m);
  ws.phi0.resize(m);
  for (int r = 0; r < m; ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    const int seg = row.segment;
    double phi = 0;
    if (seg >= 0)
      phi = kFloorLength - floorGap(c.path()[seg], c.path()[seg + 1], ws.rows[r].rim);
    else
      for (int k = row.first; k <= row.last; ++k) phi += c.spanStretch(k);
    ws.phi0[r] = phi;
    if (seg >= 0 && c.elastic() && phi > kCameInsideFloor) {
      // Held where it is, not pushed out: pushed out to the floor against the cable's pull once
      // taut, it gained energy (docs/floors.md, "Inside a floor").
      ws.target[r] = phi;
    } else if (seg >= 0 && !row.rim && phi < -kLengthSlop &&
               atRimFloor(c.path()[seg], c.path()[seg + 1])) {
      // The point sits at its rim floor: the segment is held at its length, not shortened to
      // kFloorLength. Closing the tangent length's slack (r / kFloorLength times the rim row's
      // slop) each step let a weight at a winch drum creep round it with the drum's turn
      // (docs/floors.md, "The disc of a round pulley").
      ws.target[r] = phi;
    } else if (!c.elastic() || seg >= 0) {
      ws.target[r] = phi < -kLengthSlop  ? 0.0
                     : phi > kLengthSlop ? phi - beta * (phi - kLengthSlop)
                                         : phi;
    } else if (!ws.midpoint) {  // (midpointSpringRows pulls with the energy's discrete gradient)
      const ElasticRow spring = elasticRow(ws, c, row, h);
      ws.compliance[r] = spring.compliance;
      ws.damped[r] = spring.damped;
    }
  }
}

// Each span stretches by its own share: phi1_k = (w_k P + d_k phi0_k) / (k_k h + d_k). A row
// sliding over a capstan keeps its spans' material in sum, so the sum is its constraint.
ElasticRow elasticRow(const Workspace& ws, const Cable& c, const Workspace::Row& row, double h) {
  ElasticRow spring;
  for (int k = row.first; k <= row.last; ++k) {
    const double stiffK = c.spanStiffness(k), damp = c.spanDamping(k);
    spring.compliance += row.weight(ws.rowWeights, k) / (h * (stiffK * h + damp));
    spring.damped += damp * c.spanStretch(k) / (stiffK * h + damp);
  }
  return spring;
}

double springStretchAtEnd(const Cable& c, int k, double impulse, double h) {
  const double stiffK = c.spanStiffness(k), damp = c.spanDamping(k);
  return (impulse + damp * c.spanStretch(k)) / (stiffK * h + damp);
}

// ws.WP = W P, column by column: W has a few columns (one per row), and Eigen's general product
// costs more than the arithmetic at these sizes. Kept while W and P stay as they are: the
// shortcut, the limit check and the forces all ask for the same product.
void timesImpulses(Workspace& ws, const Eigen::VectorXd& P) {
  if (ws.wpFresh && ws.wpImpulses.size() == P.size() && ws.wpImpulses == P) return;
  const Eigen::Index n = ws.W.rows(), m = ws.W.cols();
  ws.WP.setZero(n);
  for (Eigen::Index s = 0; s < m; ++s) {
    const double p = P[s];
    const double* w = ws.W.data() + s * n;
    for (Eigen::Index d = 0; d < n; ++d) ws.WP[d] += w[d] * p;
  }
  ws.wpImpulses = P;
  ws.wpFresh = true;
}

// The end-of-step state for impulses P (Box2D integrates q1 = q0 + h v1), then each row's
// end-of-step length error phi1 and its linearisation J1 W.
void linearise(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  const double h = in.h;
  timesImpulses(ws, ws.P);
  ws.v1 = ws.vStar - ws.WP;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const BodyState& s = in.bodies[ws.dofs.body[k]];
    BodyState& p = ws.predicted[ws.dofs.body[k]];
    stepPose(s, movedWith(ws, k, ws.v1.segment<3>(3 * k)), h, ws.motions[k], p);
  }
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    ws.JW.row(r).setZero();
    if (row.segment >= 0) {
      ws.phi1[r] = floorRow(ws, ws.predicted, c, row);
      addJacobianTimesW(ws, ws.floorJacobian, ws.JW.row(r));
      continue;
    }
    ws.phi1[r] = 0;
    for (int k = row.first; k <= row.last; ++k) {
      pathAhead(ws, c, k, ws.predicted);
      ws.phi1[r] += c.spanStretch(k) + ws.kin.length - c.spanKinematics(k).length;
      addJacobianTimesW(ws, ws.kin.jacobian, ws.JW.row(r));
    }
  }
}

// How far row impulses P moved for the motion: for redundant rows, whose impulses are not unique,
// the rows' rates J0 W dP (each over its diagonal, in N s), not dP itself. Two iterates that
// share the same pushes out differently between a tackle's redundant floors (its block at the top
// sheave) move the bodies the same: that is no step, let alone a growing one.
double impulseChange(Workspace& ws, const Eigen::VectorXd& next, bool redundant) {
  ws.dP = next - ws.P;
  if (!redundant) return ws.dP.lpNorm<Eigen::Infinity>();
  double change = 0;
  for (int r = 0; r < ws.dP.size(); ++r)
    if (ws.JW0(r, r) > 0)
      change = std::max(change, std::abs(ws.JW0.row(r).dot(ws.dP)) / ws.JW0(r, r));
  return change;
}

// Newton's iterations from ws.P. Stopped: the iterations ran out while the steps still shrank
// (ws.P is the last iterate, as good as it got); Close if the last step was already small.
// Diverged: a step grew instead (ws.P is not an answer).
Newton iterateNewton(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                     bool redundant, StepStats& stats) {
  const int m = static_cast<int>(ws.rows.size());
  const double h = in.h;
  double lastChange = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < (redundant ? kChordIterations : kNewtonIterations);
       ++iteration) {
    linearise(ws, in, cables);
    if (redundant) ws.JW = ws.JW0;
    // Guard (degenerate geometry): far from the start pose the end-of-step linearisation can lose
    // positive definiteness (a wrap point the predicted motion carries past its neighbour turns a
    // row's J1 against its J0: K_ii <= 0), and the LCP then answers with impulses of 1e6 N s.
    // Such a row falls back to the start-of-step Jacobian, whose J0 W is positive semidefinite.
    for (int r = 0; r < m; ++r)
      if (!(ws.JW(r, r) > 1e-3 * ws.JW0(r, r))) {
        ws.JW.row(r) = ws.JW0.row(r);
        ++stats.linearisationFallbacks;
      }
    if (ws.midpoint) midpointSpringRows(ws, cables, h);
    ws.K = ws.JW;
    ws.K.diagonal() += ws.compliance;
    ws.b.noalias() = ws.JW.lazyProduct(ws.P);  // a few rows: no GEMV kernel call
    for (int r = 0; r < m; ++r)
      ws.b[r] +=
          (ws.midpoint && cables[ws.rows[r].cable].elastic() && ws.rows[r].segment < 0 ? ws.pull[r]
           : cables[ws.rows[r].cable].elastic() && ws.rows[r].segment < 0
               ? ws.phi1[r] - ws.damped[r]
               // under the midpoint rule dphi1/dP = -(h/2) J1 W
               : (ws.midpoint ? 2 : 1) * (ws.phi1[r] - ws.target[r])) /
          h;
    LcpSolution& sol = ws.lcpSolution;
    solveLcp(ws.K, ws.b, ws.lcp, sol, redundant);
    const double change = impulseChange(ws, sol.x, redundant);
    ws.P = sol.x;
    stats.solverIterations += sol.iterations;
    stats.residual = std::max(stats.residual, sol.residual);
    if (newtonSettled(change, lastChange, ws.P.lpNorm<Eigen::Infinity>())) return Newton::Converged;
    // Steps that grow, and not by rounding (a converged iterate's change of 1e-8 |P|).
    if (!(change < lastChange) && change > 1e-3 * ws.P.lpNorm<Eigen::Infinity>())
      return Newton::Diverged;
    lastChange = change;
  }
  return newtonClose(lastChange, ws.P.lpNorm<Eigen::Infinity>()) ? Newton::Close : Newton::Stopped;
}

// 6. Newton on the end-of-step lengths phi1(P), each linearisation an LCP over all cables:
// tension >= 0, slack cables only shorten. A warm start that does not settle (a tiny mass the
// last impulses throw far) starts again from P = 0, so it only ever saves iterations.
void solveLengths(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                  StepStats& stats) {
  const int m = static_cast<int>(ws.rows.size());
  ws.phi1.resize(m);
  ws.JW.resize(m, m);
  // Redundant cables (J0 W singular): J1 W is then singular too, but not symmetric, and its
  // symmetric part indefinite, so the minimum-norm solve (tension_solver.h) would be ill posed.
  // Such an island iterates on J0 W instead (a quasi-Newton step: it still converges to the
  // end-of-step lengths, only more slowly).
  bool& redundant = ws.redundant;
  redundant = false;
  if (m > 1 && (ws.compliance.array() == 0).any()) {  // elastic rows alone: K is definite
    ws.redundancy.compute(ws.JW0);
    redundant = rankDeficient(ws.redundancy);
  }
  if (solveLinearised(ws, in, cables, redundant, stats)) return;
  if (warmStart(ws, in.h, cables)) {
    if (lastImpulsesHold(ws, in, cables) && realisable(ws, in.h) && !addsEnergy(ws, in, cables)) {
      ++stats.keptImpulses;
      return;
    }
    StepStats warm;
    const Newton warmed = iterateNewton(ws, in, cables, redundant, warm);
    if ((warmed == Newton::Converged || warmed == Newton::Close) && realisable(ws, in.h) &&
        !addsEnergy(ws, in, cables)) {
      stats.solverIterations += warm.solverIterations;
      stats.residual = std::max(stats.residual, warm.residual);
      stats.linearisationFallbacks += warm.linearisationFallbacks;
      return;
    }
    ws.P.setZero(m);
  }
  if (iterateNewton(ws, in, cables, redundant, stats) != Newton::Diverged && realisable(ws, in.h) &&
      !addsEnergy(ws, in, cables))
    return;
  // Far from linear over the step: a segment the predicted motion folds past a wrap point, where
  // pulling harder makes the end-of-step length grow (Newton's impulses grew threefold an
  // iteration, to 8e4 N on a hand's band, and the soak's fingers were thrown), or a root a whole
  // turn of a drum away (the built-in winch, stalled with its weight at the drum, found one at
  // 1e5 N, then 1e7, 1e9, ... a step), or a root no rigid row can reach (addsEnergy). The
  // start-of-step linearisation answers instead; the next sub-step corrects what it leaves.
  solveStartOfStep(ws, in, cables, redundant);
  ws.P = ws.lcpSolution.x;
  stats.solverIterations += ws.lcpSolution.iterations;
  ++stats.newtonDivergences;
  if (addsEnergy(ws, in, cables) && holdOverlongRows(ws, cables)) {
    solveStartOfStep(ws, in, cables, redundant);
    ws.P = ws.lcpSolution.x;
    stats.solverIterations += ws.lcpSolution.iterations;
    ++stats.heldIslands;
    return;  // (the rows stay long: halving the step would not shorten them)
  }
  if (missesLengths(ws, in, cables)) ++stats.unsettledIslands;
}

}  // namespace cablelab::cable_stages

namespace cablelab {

void setKeptImpulses(bool on) {
  cable_stages::keepImpulses = on;
}

}  // namespace cablelab
