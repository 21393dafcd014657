// Stage 5b of the cable solve (cable_solver.cpp): a body that knocks against its pulley bounces
// off it with its shapes' restitution (docs/floors.md, "Bouncing off a pulley"), and no bounce
// ends its step with more energy than it began with ("The disc of a round pulley").
#include "engine/dynamics/cable_solver_stages.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/dynamics/floors.h"

namespace cablelab::cable_stages {
namespace {

constexpr double kFreeFloor = 1.0;  // m: a floor row's target this far past its start never binds

// The island's energy (kinetic, gravity's and the elastic rows'; a floor row holds none) at the
// start of the step (`atEnd` false) or at its end for the impulses ws.P. `kinetic` gets its
// kinetic part.
double islandEnergy(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables,
                    bool atEnd, double& kinetic) {
  if (atEnd) linearise(ws, in, cables);  // v1, the end poses and phi1 at ws.P
  const Eigen::VectorXd& v = atEnd ? ws.v1 : ws.v0;
  kinetic = 0;
  for (Eigen::Index d = 0; d < v.size(); ++d)
    if (ws.invM[d] > 0) kinetic += 0.5 * v[d] * v[d] / ws.invM[d];
  double energy = kinetic;
  for (size_t k = 0; k < ws.dofs.body.size(); ++k) {
    const int b = ws.dofs.body[k];
    const Vec2& x = atEnd ? ws.predicted[b].position : in.bodies[b].position;
    if (in.bodies[b].invMass > 0) energy -= in.gravity.dot(x) / in.bodies[b].invMass;
  }
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    const double phi = atEnd ? ws.phi1[r] : ws.phi0[r];
    if (row.segment < 0 && c.elastic() && phi > 0)
      energy += 0.5 * c.spanStiffness(row.first) * phi * phi;
  }
  return energy;
}

// Of the larger kinetic energy, at the start or at the end of the free step: what a bounce may
// end above the larger of their energies by.
constexpr double kBounceEnergyAllowance = 0.01;

// Of the kinetic energy at the start: what a midpoint step whose floor pushes without a knock may
// end above its start by (judgeFloorOnMidpoint).
constexpr double kRestingFloorAllowance = 1e-3;

constexpr int kBounceHalvings = 6;  // of the share of a bounce that gains (to 1/64 of it)

}  // namespace

// 5b. Bouncing off a pulley (docs/floors.md): a floor row whose segment closes at v, faster than
// kSlowestBounce, and that the step, solved without it, takes past its floor bounces with e, the
// larger restitution of the two bodies' shapes (Box2D's b2MixRestitution; the world has none).
// floorBounces leaves such rows free (true if any) for a first solve; bounceTargets then asks for
// the row's end value of that free step opened by (1 + e) v h: the knock adds (1 + e) v to the
// rate the step's own pulls (the rigid cable, a bungee's spring, gravity) give the segment. The
// body turns back where the step starts, up to v h short of its floor: at that place it comes
// back from a knock at the speed it had there. Asked for e v at the end of the step instead, the
// knock ignored the pulls over the step: a bungee's bob, turned back against its spring's pull T,
// gained T v h. Reflected at the floor, its velocity, (gap1 - gap0) / h as Box2D moves it, fell
// short by (1 + e) (gap0 - 1 cm) / h. e = 0 keeps lengthTargets' plastic stop.
double floorKnock(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int r,
                  double& phi) {
  const Workspace::Row& row = ws.rows[r];
  if (row.segment < 0 || ws.restitution.empty()) return 0;
  auto restitution = [&](int body) {
    return body >= 0 && body < static_cast<int>(ws.restitution.size()) ? ws.restitution[body] : 0.0;
  };
  const Cable& c = cables[row.cable];
  const double e = std::max(restitution(c.path()[row.segment].body),
                            restitution(c.path()[row.segment + 1].body));
  if (!(e > 0)) return 0;
  phi = floorRow(ws, in.bodies, c, row);  // kFloorLength - gap, at the start
  // Inside an elastic cable's floor already: held where it is (lengthTargets), not thrown out.
  if (c.elastic() && phi > kCameInsideFloor) return 0;
  double closing = 0;  // d phi / dt at the start of the step
  for (const BodyJacobian& j : ws.floorJacobian) {
    const BodyState& b = in.bodies[j.body];
    closing += j.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
  }
  // Slow, or too far off to arrive within the step (pulls may speed it up to twice as fast).
  if (closing < kSlowestBounce || -phi > 2 * closing * in.h) return 0;
  return (1 + e) * closing * in.h;
}

// 5b for a rigid cable's row (docs/cables.md, "Catching from slack"): a slack rope that closes at
// v, faster than kSlowestBounce, near enough to come taut within the step, catches with e, the
// largest restitution of the bodies it runs over (b2MixRestitution), the way a segment bounces
// off its floor: left free for a first solve, then, if that solve takes it past its length,
// opened by (1 + e) v h, so that e^2 of the kinetic energy closing along it comes back. e = 0
// keeps lengthTargets' plastic catch; elastic rows catch on their spring.
double ropeCatch(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables, int r,
                 double& phi, Workspace::Bounce& caught) {
  const Workspace::Row& row = ws.rows[r];
  const Cable& c = cables[row.cable];
  if (row.segment >= 0 || c.elastic() || ws.restitution.empty()) return 0;
  phi = ws.phi0[r];
  if (!(phi < -kLengthSlop)) return 0;  // taut: no catch
  double e = 0;
  for (const WrapPoint& p : c.path())
    if (p.body >= 0 && p.body < static_cast<int>(ws.restitution.size()))
      e = std::max(e, ws.restitution[p.body]);
  if (!(e > 0)) return 0;
  double closing = 0;  // d phi / dt at the start of the step
  for (int k = row.first; k <= row.last; ++k)
    for (const BodyJacobian& j : c.spanKinematics(k).jacobian) {
      const BodyState& b = in.bodies[j.body];
      closing += j.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
    }
  if (closing < kSlowestBounce || -phi > 2 * closing * in.h) return 0;
  caught = {r, 0, 0, true, e, phi, closing};
  return (1 + e) * closing * in.h;
}

bool floorBounces(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  ws.bounces.clear();
  for (int r = 0; r < static_cast<int>(ws.rows.size()); ++r) {
    double phi = 0;
    Workspace::Bounce bounce{r};
    double opening = floorKnock(ws, in, cables, r, phi);
    if (!(opening > 0)) opening = ropeCatch(ws, in, cables, r, phi, bounce);
    if (!(opening > 0)) continue;
    bounce.opening = opening;
    bounce.held = ws.target[r];
    ws.bounces.push_back(bounce);
    ws.target[r] = phi + kFreeFloor;  // free for the first solve
  }
  return !ws.bounces.empty();
}

namespace {

// A rope's catch gives back e^2 of the energy closing along it when it comes taut, at v_c, not at
// the start's v0: the free step's pulls a (from its end value) speed it up over the slack,
// v_c^2 = v0^2 - 2 a phi0. Its end rate v1 is the one whose step, as Box2D moves it (phi1 = phi0
// + v1 h, the pulls doing a h v1 of work per unit of the row's mass), ends (1 - e^2) v_c^2 / 2
// down: v1^2 / 2 - a h v1 = v0^2 / 2 - (1 - e^2) v_c^2 / 2. Opened by (1 + e) v0 h instead, a slow
// bob at 30 Hz, closing 2 m/s, gave back 39% at e = 0.5 (docs/floors.md, "A rigid rope caught from
// slack").
double catchTarget(const Workspace::Bounce& b, double phi1, double h) {
  const double v0 = b.closing, pulled = (phi1 - b.start) / h - v0;  // a h
  const double caught2 = std::max(0.0, v0 * v0 - 2 * (pulled / h) * b.start);
  const double e2 = b.restitution * b.restitution;
  const double v1 =
      pulled - std::sqrt(std::max(0.0, pulled * pulled + v0 * v0 - (1 - e2) * caught2));
  // Never more back than the opening (1 + e) v0 h gives: in a swing the pulls along the rope are
  // partly the turn's, which does no work: at e = 1 later catches gained up to 3.4% of theirs.
  return std::max(b.start + v1 * h, phi1 - b.opening);
}

void bounceTargets(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  linearise(ws, in, cables);                     // phi1 at the free step's impulses
  for (const Workspace::Bounce& b : ws.bounces)  // only rows the free step takes past the floor
    ws.target[b.row] = !(ws.phi1[b.row] > 0) ? b.held
                       : b.catchesRope       ? catchTarget(b, ws.phi1[b.row], in.h)
                                             : ws.phi1[b.row] - b.opening;
}

}  // namespace

namespace {

// Whether the island's knocks are taken as impulses at the start of the step: every cable row
// elastic, so no row passes an impulse on within the step (a rigid rope throws the other side
// back up with the knocked one; its knock stays a target, bounceTargets).
bool knocksAsImpulses(const Workspace& ws, std::span<const Cable> cables) {
  return std::all_of(ws.rows.begin(), ws.rows.end(),
                     [&](const Workspace::Row& row) { return cables[row.cable].elastic(); });
}

// The knock on an island of elastic rows (docs/floors.md, "Bouncing off a pulley"): the floor
// rows' impulses that turn each segment's closing speed v into -e v at the start of the step,
// from J0 W (a spring passes no impulse), added to the start velocities; the step is then solved
// from there with the floors plain. Asked of the end of the step instead (the free step's end
// value opened by (1 + e) v h), the knock ignored how the bounce itself stretches the rope: an
// elastic Atwood's light side, turned back while its heavy side still fell, had the pulls of a
// free step that passed through its point pulley (where the rope's length folds), and stopped
// dead, losing up to 7.7 J of a 17 J kinetic energy in the step. A knock that gains beyond the
// allowance takes the largest share of it that does not (halving), as solveBouncing.
void knockAsImpulses(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                     StepStats& stats) {
  const int count = static_cast<int>(ws.bounces.size());
  Eigen::MatrixXd rowsW(count, count);
  Eigen::VectorXd turn(count);
  for (int i = 0; i < count; ++i) {
    const Workspace::Bounce& b = ws.bounces[i];
    ws.target[b.row] = b.held;
    turn[i] = b.opening / in.h;  // (1 + e) v
    for (int j = 0; j < count; ++j) rowsW(i, j) = ws.JW0(b.row, ws.bounces[j].row);
  }
  const Eigen::VectorXd knock = rowsW.completeOrthogonalDecomposition().solve(turn).cwiseMax(0.0);
  Eigen::VectorXd impulses = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(ws.rows.size()));
  for (int i = 0; i < count; ++i) impulses[ws.bounces[i].row] = knock[i];
  const Eigen::VectorXd dv = ws.W * impulses, vStar = ws.vStar, v0 = ws.v0;
  double kinetic0, ignored;
  const double start = islandEnergy(ws, in, cables, false, kinetic0);
  const double allowed = start + kBounceEnergyAllowance * kinetic0;
  auto energyWithShare = [&](double share) {
    ws.vStar = vStar - share * dv;
    ws.v0 = v0 - share * dv;
    newtonOnLengths(ws, in, cables, stats);
    return islandEnergy(ws, in, cables, true, ignored);
  };
  // Under the midpoint rule the step is judged once solved, its rows pulling along the discrete
  // gradient (stage 6e): at the start-of-step J a light side whirling past its pulley reads far
  // above its start, and a share taken then would stop it (midpointKnockGains).
  if (ws.midpoint && knock.allFinite()) {
    ws.knockedOnMidpoint = true;
    ws.knockAllowed = allowed;
    energyWithShare(1);
    return;
  }
  if (!(knock.allFinite()) || energyWithShare(1) <= allowed) return;
  double kept = 0, gains = 1;
  bool lastKept = false;
  for (int i = 0; i < kBounceHalvings; ++i) {
    const double share = 0.5 * (kept + gains);
    lastKept = energyWithShare(share) <= allowed;
    (lastKept ? kept : gains) = share;
  }
  if (!lastKept) energyWithShare(kept);
}

}  // namespace

// A floor row under the midpoint rule with no knock (hasFloorRow): a light side resting
// at its point pulley while the heavy side bounces on the rope stops nothing, and the
// backward-Euler spring damped the bounce. The step keeps the rule and is
// judged once solved like a knock (midpointKnockGains), with a tighter allowance: a floor that
// stops a moving body throws it back and gains (docs/floors.md, "A resting light side").
void judgeFloorOnMidpoint(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  double kinetic0;
  const double start = islandEnergy(ws, in, cables, false, kinetic0);
  ws.knockedOnMidpoint = true;
  ws.knockAllowed = start + kRestingFloorAllowance * kinetic0;
}

// The end's energy with each one-span elastic row at its exact length there (pathAhead): a light
// side that sweeps past its point pulley within the step folds the rope's length, which the
// linearised stretch does not follow (docs/floors.md, "Elastic ropes: the knock as an impulse").
bool midpointKnockGains(Workspace& ws, const CableSolveInput& in, std::span<const Cable> cables) {
  double ignored;
  double energy = islandEnergy(ws, in, cables, true, ignored);  // the end poses in ws.predicted
  for (size_t r = 0; r < ws.rows.size(); ++r) {
    const Workspace::Row& row = ws.rows[r];
    const Cable& c = cables[row.cable];
    if (row.segment >= 0 || !c.elastic() || row.first != row.last) continue;
    pathAhead(ws, c, row.first, in.bodies);
    const double now = ws.kin.length;
    pathAhead(ws, c, row.first, ws.predicted);
    const double exact = std::max(0.0, ws.phi0[static_cast<Eigen::Index>(r)] + ws.kin.length - now);
    const double linear = std::max(0.0, ws.phi1[static_cast<Eigen::Index>(r)]);
    energy += 0.5 * c.spanStiffness(row.first) * (exact * exact - linear * linear);
  }
  return energy > ws.knockAllowed;
}

// 5b, after floorBounces: a first solve with the bouncing floors left free, then the bounce. A
// bounce may end the step with no more energy than it starts with or the free step (which passes
// through the floor) ends with: a bungee's bob that struck a round pulley from the side, its rope
// pulling along the rim, was sent back along the rim's normal and the rope stretched, and the
// segment's two floor rows (along it and at the rim, floors.h) each asked for a knock of their
// own: up to twice the energy in a step (docs/floors.md, "The disc of a round pulley"). Such a
// step takes a share s of the bounce's targets, between the plastic stop's (s = 0) and the
// bounce's, the one whose energy, taken as growing with s^2 from the plastic stop's, is half the
// allowance short of the most allowed; if that gains too, the largest that does not, halving.
// Stopped plastically instead, a bob knocking a drum lost 38% of a busy scene's energy scale;
// bisected alone, 3% of it.
void solveBouncing(Workspace& ws, const CableSolveInput& in, std::span<Cable> cables,
                   StepStats& stats) {
  if (knocksAsImpulses(ws, cables)) {
    knockAsImpulses(ws, in, cables, stats);
    return;
  }
  // The free step is a probe: it may pass a body through its point pulley, where no length is
  // smooth, and miss its lengths. Counted unsettled, World halved the step down to a gap the
  // bounce could no longer open (docs/floors.md, "Bouncing off a pulley").
  const int unsettled = stats.unsettledIslands, held = stats.heldIslands;
  newtonOnLengths(ws, in, cables, stats);
  stats.unsettledIslands = unsettled;
  stats.heldIslands = held;
  double kinetic0, kinetic1, ignored;
  const double start = islandEnergy(ws, in, cables, false, kinetic0);
  const double free = islandEnergy(ws, in, cables, true, kinetic1);
  double allowance = kBounceEnergyAllowance * std::max(kinetic0, kinetic1), trusted = free;
  if (free > start + allowance) {  // a free step through the pulley gains: no bound for a bounce
    trusted = start;
    allowance = kBounceEnergyAllowance * kinetic0;
  }
  const double allowed = std::max(start, trusted) + allowance, aim = allowed - 0.5 * allowance;
  bounceTargets(ws, in, cables);
  newtonOnLengths(ws, in, cables, stats);
  const double full = islandEnergy(ws, in, cables, true, ignored);
  if (full <= allowed) return;
  std::vector<double> bounced;  // (rare: a bounce that gains)
  for (const Workspace::Bounce& b : ws.bounces) bounced.push_back(ws.target[b.row]);
  auto energyWithShare = [&](double share) {
    for (size_t i = 0; i < ws.bounces.size(); ++i) {
      const Workspace::Bounce& b = ws.bounces[i];
      ws.target[b.row] = b.held + share * (bounced[i] - b.held);
    }
    newtonOnLengths(ws, in, cables, stats);
    return islandEnergy(ws, in, cables, true, ignored);
  };
  const double plastic = energyWithShare(0);
  if (plastic >= allowed) return;
  double kept = 0, gains = std::sqrt(std::clamp((aim - plastic) / (full - plastic), 0.0, 1.0));
  if (const double first = energyWithShare(gains); first <= allowed) {
    // Once more along the line through it and the full bounce (in s^2): the model's first guess
    // fell short by up to 5% of a busy scene's scale.
    if (first >= aim - allowance || !(full > first)) return;
    const double s2 = gains * gains + (aim - first) * (1 - gains * gains) / (full - first);
    if (energyWithShare(std::sqrt(std::min(s2, 1.0))) <= allowed) return;
    kept = gains;
    gains = 1;
  }
  bool lastKept = false;
  for (int i = 0; i < kBounceHalvings; ++i) {
    const double share = 0.5 * (kept + gains);
    lastKept = energyWithShare(share) <= allowed;
    (lastKept ? kept : gains) = share;
  }
  if (lastKept) return;
  for (size_t i = 0; i < ws.bounces.size(); ++i)
    ws.target[ws.bounces[i].row] = ws.bounces[i].held + kept * (bounced[i] - ws.bounces[i].held);
  newtonOnLengths(ws, in, cables, stats);
}

}  // namespace cablelab::cable_stages
