// Implicit midpoint cable solve with discrete gradients (rationale in midpoint_solver.h).
#include "engine/dynamics/midpoint_solver.h"

#include <algorithm>
#include <cmath>

#include "engine/dynamics/floors.h"
#include "engine/dynamics/length_targets.h"
#include "engine/dynamics/settled_energy.h"

namespace cablelab {

namespace {

constexpr int kIterations = 40;
constexpr double kPositionTolerance = 1e-12;  // m: end-of-step pose settled
constexpr int kLazyProductSize = 64;  // rows times dofs up to which products go coefficient-wise
constexpr int kFloorIterations = 2;   // a floor pushing on as many first iterations: given up
// Largest omega h of a taut rigid cable's swing the main solve keeps: its geometric stiffness,
// which acts from omega h = 0.22 on (geometric_stiffness.cpp), damps faster ones.
constexpr double kMaxMainSolveSwingOmegaH = 0.2;

// Discrete gradient of V = k/2 max(0, phi)^2 between phi0 and phi1, and its phi1-derivative.
// With both ends taut (or both slack) they are k (phi0 + phi1) / 2 and k / 2 in closed form: the
// quotients (V1 - V0) / d and its derivative, with d = phi1 - phi0, lose to rounding what they
// divide by d and d^2, and for a cable nearly at rest (d ~ 1e-10 m) the slope came out hundreds
// of times k: the Newton of a platform resting on its cables did not settle, and the step was
// halved up to 16 times, 1000-4000 iterations, each fallback leaving it swaying at 1e-9 m/s.
struct SpringSecant {
  double tension, slope;
};
SpringSecant springSecant(double k, double phi0, double phi1) {
  if (phi0 >= 0 && phi1 >= 0) return {0.5 * k * (phi0 + phi1), 0.5 * k};
  if (phi0 <= 0 && phi1 <= 0) return {0.0, 0.0};
  // Crossing zero: |d| is at least the taut end's stretch, so nothing cancels.
  const double d = phi1 - phi0;
  const double v0 = phi0 > 0 ? phi0 * phi0 : 0.0, v1 = phi1 > 0 ? phi1 * phi1 : 0.0;
  const double tension = 0.5 * k * (v1 - v0) / d;
  const double dv1 = phi1 > 0 ? 2 * phi1 : 0.0;
  return {tension, 0.5 * k * (dv1 * d - (v1 - v0)) / (d * d)};
}

// The spring of a cable whose axial mode the step does not resolve (elasticMode h above
// MidpointSolver::kMaxElasticOmegaH), taken at the end of the step: k phi1, slack or not, since
// the LCP's P >= 0 makes it k max(0, phi1). Its work over the step, k max(0, phi1) (phi1 - phi0),
// is at least V(phi1) - V(phi0) (V convex), so it can only take energy: it damps the mode the step
// cannot follow (by k/2 (phi1 - phi0)^2 a taut step) and leaves the slow motion the midpoint rule
// keeps (docs/cables.md, "Energy"). The secant would keep the fast mode too, ringing at the
// step's rate.
SpringSecant springAtEnd(double k, double phi1) {
  return {k * phi1, k};
}

// The fastest the axial mode of an elastic cable can get on its current path (rad/s):
// sqrt(k J M^-1 J^T) with J at its largest. Per body, each segment end on it whose other end is
// on another body adds at most a unit vector to J's translation and |r| to its turn, so
// J M^-1 J^T <= sum over bodies of n^2 / m + (sum |r|)^2 / I. Bounded rather than taken at J
// now, since J of a point that just joined is zero (theorem 1) and grows within steps. (Counted
// per point, with both of a vertex's segments whichever body the other end is on, it read twice
// this and gave an undamped sling on a light square to the damped main solve.)
double elasticMode(const Cable& c, std::span<const BodyState> bodies) {
  struct Ends {
    int body;
    double count = 0, arms = 0;
  };
  static thread_local std::vector<Ends> perBody;  // a path touches few bodies; kept: no allocation
  perBody.clear();
  auto add = [&](const WrapPoint& w) {
    if (w.body < 0) return;
    auto e = std::find_if(perBody.begin(), perBody.end(),
                          [&](const Ends& x) { return x.body == w.body; });
    if (e == perBody.end()) e = perBody.insert(perBody.end(), Ends{w.body});
    e->count += 1;
    e->arms += w.local.norm();
  };
  const auto& path = c.path();
  for (size_t i = 0; i + 1 < path.size(); ++i)
    if (path[i].body != path[i + 1].body || path[i].radius != path[i + 1].radius)
      add(path[i]), add(path[i + 1]);  // the segments that J counts (cable_kinematics.cpp)
  double bound = 0;
  for (const Ends& e : perBody) {
    const BodyState& b = bodies[e.body];
    bound += b.invMass * e.count * e.count + b.invInertia * e.arms * e.arms;
  }
  return std::sqrt(c.parameters().stiffness * bound);
}

// The rigid-cable length target at the end of the step (as in the main solve): `share` is the
// step over the nominal sub-step, so a step cut at an event corrects only its share.
double rigidTarget(double phi, double share) {
  return phi < -kLengthSlop  ? 0.0
         : phi > kLengthSlop ? phi - kBaumgarte * share * (phi - kLengthSlop)
                             : phi;
}

// A floor row (floors.h) at the end of the step, kFloorLength - n . (x_to - x_from), and its
// exact discrete gradient into `g`. The contacts are those at the start of the step (a circle's
// tangent point carried with its centre) and n the row's direction (floorNormal), as in the main
// solve: for a body heading into its pulley (or rolling over a wheel's rim, where the tangent
// length comes back up) the segment's direction then, along which passing through goes negative
// instead of looking allowed.
double floorRow(const WrapPoint& p, const WrapPoint& q, const Vec2& n,
                std::span<const BodyState> q0, std::span<const BodyState> q1,
                std::vector<BodyJacobian>& g) {
  const Vec2 from = p.leaving(), to = q.arriving();
  g.clear();
  double along = 0;
  for (int e = 0; e < 2; ++e) {
    const WrapPoint& w = e == 0 ? p : q;
    const double sign = e == 0 ? -1.0 : 1.0;  // d(along) / d(x of this end)
    const Vec2 offset = (e == 0 ? from : to) - w.world;
    if (w.body < 0) {
      along += sign * n.dot(w.world + offset);
      continue;
    }
    const BodyState &s0 = q0[w.body], &s1 = q1[w.body];
    along += sign * n.dot(s1.position + rotate(w.local, s1.angle) + offset);
    // R(theta1) r - R(theta0) r = sinc(dtheta / 2) dtheta perp(R(theta_mid) r), exactly.
    const double half = 0.5 * (s1.angle - s0.angle);
    const double sinc = std::abs(half) < 1e-8 ? 1 - half * half / 6 : std::sin(half) / half;
    const Vec2 arm = sinc * perp(rotate(w.local, 0.5 * (s0.angle + s1.angle)));
    g.push_back({w.body, -sign * Vec3(n.x(), n.y(), n.dot(arm))});
  }
  return kFloorLength - along;
}

// The velocity of a path point (zero on a point fixed in the world).
Vec2 wrapPointVelocity(const WrapPoint& w, std::span<const BodyState> bodies) {
  return w.body < 0 ? Vec2(Vec2::Zero()) : pointVelocity(bodies[w.body], w.world);
}

// Whether some segment of `path` with an end on a moving body turns (the ends' velocities differ
// across it, a body spins) or hangs off the line of gravity, so that its body swings. Tolerances
// far below any swing worth its energy: a swing that small changing integrator loses nothing
// measurable.
bool pathSwings(const std::vector<WrapPoint>& path, std::span<const BodyState> bodies,
                const Vec2& gravity) {
  constexpr double kAcrossSpeed = 1e-7;  // m/s
  constexpr double kOffGravity = 1e-7;   // rad
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const WrapPoint &p = path[i], &q = path[i + 1];
    const bool movesP = p.body >= 0 && moves(bodies[p.body]);
    const bool movesQ = q.body >= 0 && moves(bodies[q.body]);
    if (!movesP && !movesQ) continue;
    const Vec2 d = q.arriving() - p.leaving();
    const double length = d.norm();
    if (!(length > 0)) continue;
    const Vec2 u = d / length;
    if (std::abs(cross(u, wrapPointVelocity(q, bodies) - wrapPointVelocity(p, bodies))) >
        kAcrossSpeed)
      return true;
    if (std::abs(cross(u, gravity)) > kOffGravity * gravity.norm()) return true;
    for (const WrapPoint* w : {&p, &q})
      if (w->body >= 0 && bodies[w->body].angularVelocity != 0) return true;
  }
  return false;
}

// Whether a cable over fixed point pulleys (an Atwood machine: both ends on bodies, every point
// between them a point pulley fixed in the world, at least one) swings (pathSwings). Other rigid
// cables keep the solve they had: a rope from an anchor (a pendulum, over a pulley or not), a
// chain's links (the main solve's sparse path for big islands), ropes over circles or polygons;
// unless taut and swinging faster than the main solve resolves (applies, tautSwingRate), or
// settled taut over pulleys (swingsOverPulleys).
bool rigidCableSwings(const Cable& c, std::span<const BodyState> bodies, const Vec2& gravity) {
  const auto& path = c.path();
  if (path.size() < 3 || path.front().body < 0 || path.back().body < 0) return false;
  for (size_t i = 1; i + 1 < path.size(); ++i)
    if (path[i].kind != WrapPoint::Kind::Point || path[i].body >= 0) return false;
  return pathSwings(path, bodies, gravity);
}

// Whether a rigid cable over pulleys swings (pathSwings). A rope that wraps and unwraps a peg took
// the midpoint rule while wrapped and the main solve while straight, and each switch locked in the
// main solve's energy swing: a bob round a peg lost 37% of its swing in 10 minutes at 60 Hz, 91%
// round a square one (docs/swings.md). Hung straight (an Atwood machine at rest), it keeps Box2D's
// integration, exact there.
bool swingsOverPulleys(const Cable& c, std::span<const BodyState> bodies, const Vec2& gravity) {
  return c.pulleyCount() > 0 && pathSwings(c.path(), bodies, gravity);
}

// How fast a taut rigid cable's segments turn (rad/s): the ends' velocities across each segment
// with an end on a moving body, over its length. Its tension says the same once solved
// (transverseMode, which the main solve's stiffness acts on: after a catch the tension is the
// catch's), but a cable caught at the start of a run has none yet.
double tautSwingRate(const Cable& c, std::span<const BodyState> bodies) {
  if (c.stretch() < -kLengthSlop) return 0;
  const auto& path = c.path();
  double fastest = 0;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const WrapPoint &p = path[i], &q = path[i + 1];
    if (p.body == q.body ||
        !((p.body >= 0 && moves(bodies[p.body])) || (q.body >= 0 && moves(bodies[q.body]))))
      continue;
    const Vec2 d = q.world - p.world;
    const double length = d.norm();
    if (length > 1e-9)
      fastest = std::max(
          fastest, std::abs(cross(d, wrapPointVelocity(q, bodies) - wrapPointVelocity(p, bodies))) /
                       (length * length));
  }
  return fastest;
}

// Whether the step takes a point of one of `rows` (cable rows) into its floor at a circle of the
// path, out of it at the start: the tangent length to the rim below kFloorLength (floors.h,
// rimGap). The midpoint solve's floor rows run along the segment only, and a point that comes at
// the rim from the side slides past the tangent point into the disc; the main solve's rim row
// stops it. Taut or slack (needsDiscFloor): a bungee's bob swung onto a world drum went 1.6 cm
// into it, and the rope, holding it there, later threw it out with 10 times its energy
// (docs/floors.md, "The disc of a round pulley").
bool entersRimFloor(std::span<const BodyState> bodies, std::span<const BodyState> predicted,
                    std::span<const Cable> cables, std::span<const int> rows,
                    std::span<const int> dofOfBody) {
  constexpr double kInside = kFloorLength - 0.1 * kFloorLength;
  for (const int index : rows) {
    const Cable& c = cables[index];
    if (!hasFloors(c)) continue;
    const auto& path = c.path();
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      const int rim = rimEnd(path[i], path[i + 1]);
      if (rim < 0) continue;
      const WrapPoint &circle = path[i + rim], &point = path[i + 1 - rim];
      if (point.body < 0 || dofOfBody[point.body] < 0) continue;
      Vec2 g;
      const double gap0 = rimGap(point.body, worldPoint(bodies, point.body, point.local),
                                 worldPoint(bodies, circle.body, circle.local), circle.radius, g);
      const double gap1 =
          rimGap(point.body, worldPoint(predicted, point.body, point.local),
                 worldPoint(predicted, circle.body, circle.local), circle.radius, g);
      if (gap0 >= kInside && gap1 < kInside) return true;
    }
  }
  return false;
}

}  // namespace

// Taut at the end of the kSettledTautSteps before the step. Not asked of its length now: the
// midpoint rule leaves a rigid rope within kLengthSlop of its length either side, and one round a
// round peg that ended just short of it went to the main solve for a step and lost 0.25% of its
// swing there.
bool MidpointSolver::settledTaut(int cable) const {
  return cable < static_cast<int>(tautSteps_.size()) && tautSteps_[cable] >= kSettledTautSteps;
}

bool MidpointSolver::applies(std::span<const BodyState> bodies, std::span<const Cable> cables,
                             std::span<const int> which, std::span<const char> excluded, double h,
                             double subStep, const Vec2& gravity) {
  bool wanted = false, any = false, unresolved = false;
  // A check that can only set `wanted` is skipped once it is set (a third of this per Atwood
  // machine); one that can rule the island out is not.
  for (const int index : which) {
    const Cable& c = cables[index];
    bool pulls = false;
    for (const auto& e : c.kinematics().jacobian) {
      const BodyState& b = bodies[e.body];
      if (moves(b)) {
        if (excluded[e.body]) return false;
        pulls = true;
      } else if (driven(b)) {
        return false;  // a kinematic body drives it: the main solve moves it (item "Driven")
      }
    }
    if (!pulls) continue;
    any = true;
    const auto& path = c.path();
    // Wheels that grip the cable (spans) are left to the main solve (docs/wheels.md).
    if (c.spanCount() > 1) return false;
    // A pulley on a moving body, wrapped or not: a cable whose moving pulley came off it keeps
    // the midpoint rule, since switching between it and Box2D's own integration at every
    // engagement locks in the latter's energy swing each time (a weight swinging on and off a
    // hung square gained 19% in 60 s).
    for (int j = 0; j < c.pulleyCount(); ++j)
      wanted |= c.pulleyBody(j) >= 0 && moves(bodies[c.pulleyBody(j)]);
    // A rigid cable over pulleys that swings, taut at the start of the step and for the
    // kSettledTautSteps before it (swingsOverPulleys).
    wanted |=
        !wanted && !c.elastic() && settledTaut(index) && swingsOverPulleys(c, bodies, gravity);
    // A loop, both ends on one body that turns (a frame hung on a nail): it swings on the loop, a
    // mode whose energy Box2D's integration swings by about omega h / 2 (the frame: 15% of its
    // largest kinetic energy over 60 s at 1 sub-step).
    const int loop = path.front().body;
    wanted |=
        loop >= 0 && path.back().body == loop && moves(bodies[loop]) && bodies[loop].invInertia > 0;
    // An elastic cable whose axial mode the step does not resolve pulls with its spring at the
    // end of the step (springAtEnd), which damps that mode. A moving body the cable wraps or
    // passes over (a point caught on a stiff band) is held sideways by the tension too, a mode
    // as stiff as the cable's that the midpoint rule would keep ringing: the main solve's
    // backward Euler damps both.
    if (c.elastic() && elasticMode(c, bodies) * h > kMaxElasticOmegaH) {
      unresolved = true;
      for (size_t i = 1; i + 1 < path.size(); ++i)
        if (path[i].body >= 0 && moves(bodies[path[i].body])) return false;
    }
    // A rigid cable whose bodies swing (an Atwood machine's side going like a pendulum): Box2D's
    // integration swings that mode's energy by about omega h / 2 (2.3% of the largest kinetic
    // energy of an Atwood pair at 60 Hz), the midpoint rule by 5e-5. One that only runs along
    // itself (bodies hung straight under their pulleys) keeps Box2D's integration, exact there.
    wanted |= !wanted && !c.elastic() && rigidCableSwings(c, bodies, gravity);
    // A taut rigid cable whose bodies swing round faster than the main solve's step resolves (a
    // bob whirled on a tether): there its geometric stiffness (geometric_stiffness.h), taken
    // about the start pose, damps the swing by 1 / (1 + (omega h)^2) a step, 10% at omega h =
    // 1/3, and a whirl slows to omega h = 0.22, where the stiffness stops acting (docs/knocks.md,
    // "Rigid tethers"). Judged over the whole sub-step: a part of it cut short (a refinement's
    // rest, a wrap event's) handed to the main solve turned the rate twice (start_rates.h), and
    // the tension read off by m (the rate's change) / h (docs/model.md, "Coupling to Box2D").
    if (!wanted && !c.elastic() && which.size() <= kMaxCablesWithUnresolvedSpring) {
      const std::span<const int> alone(&index, 1);
      const double swing =
          std::max(transverseMode(bodies, cables, alone), tautSwingRate(c, bodies));
      wanted |= swing * std::max(h, subStep) > kMaxMainSolveSwingOmegaH;
    }
    wanted |= c.elastic();  // resolved or not: an unresolved spring is damped (springAtEnd)
    // A segment near its floor (a body nearing its pulley).
    for (size_t i = 0; !wanted && i + 1 < path.size(); ++i)
      wanted |= nearFloor(path, i, bodies, h, Vec2::Zero(), [](int) { return true; });
  }
  if (unresolved && static_cast<int>(which.size()) > kMaxCablesWithUnresolvedSpring) return false;
  return any && wanted;
}

// q1 = q0 + h v_b, the midpoint pose, and each row's discrete gradient and end-of-step stretch.
void MidpointSolver::evaluate(std::span<const BodyState> bodies, std::span<const Cable> cables,
                              double h) {
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const BodyState& s = bodies[bodyOfDof_[k]];
    BodyState& p = predicted_[bodyOfDof_[k]];
    p.position = s.position + h * vb_.segment<2>(3 * k);
    p.angle = s.angle + h * vb_[3 * k + 2];
    midpoint_[bodyOfDof_[k]].position = 0.5 * (s.position + p.position);
    midpoint_[bodyOfDof_[k]].angle = 0.5 * (s.angle + p.angle);
  }
  chords_.move(bodies, predicted_, midpoint_, bodyOfDof_);
  for (size_t r = 0; r < rows_.size(); ++r) {
    const Cable& c = cables[rows_[r]];
    if (const int seg = segment_[r]; seg >= 0) {
      phi1_[r] = floorRow(c.path()[seg], c.path()[seg + 1], normals_[r], bodies, predicted_,
                          gradients_[r]);
      continue;
    }
    if (chordPath_[r] >= 0) {
      phi1_[r] = phi0_[r] + chords_.discreteGradient(chordPath_[r], gradients_[r]) - c.length();
      continue;
    }
    path_.assign(c.path().begin(), c.path().end());
    const double length1 = lengthDiscreteGradient(path_, bodies, predicted_, gradients_[r]);
    phi1_[r] = phi0_[r] + length1 - c.length();
  }
}

double MidpointSolver::fastCatchStep(std::span<const BodyState> bodies,
                                     std::span<const Cable> cables, std::span<const int> which,
                                     double dt, double maxOmegaDt) {
  const double omega = transverseMode(bodies, cables, which);
  if (!(omega * dt > maxOmegaDt)) return dt;
  return fixedBetweenEnds(bodies, cables, which) ? dt / std::ceil(omega * dt / maxOmegaDt)
                                                 : maxOmegaDt / omega;
}

bool MidpointSolver::fixedBetweenEnds(std::span<const BodyState> bodies,
                                      std::span<const Cable> cables, std::span<const int> which) {
  for (const int index : which) {
    if (cables[index].elastic()) return false;  // a rigid rope's catch (docs/swings.md)
    const auto& path = cables[index].path();
    for (size_t i = 1; i + 1 < path.size(); ++i)
      if (path[i].body >= 0 && moves(bodies[path[i].body])) return false;
  }
  return true;
}

double MidpointSolver::transverseMode(std::span<const BodyState> bodies,
                                      std::span<const Cable> cables, std::span<const int> which) {
  double fastest = 0;
  for (const int index : which) {
    const Cable& c = cables[index];
    const auto& path = c.path();
    double invMass = 0, curvature = 0;
    for (size_t i = 0; i < path.size(); ++i) {
      if (path[i].body >= 0) invMass = std::max(invMass, bodies[path[i].body].invMass);
      if (i + 1 < path.size())
        curvature += 1.0 / std::max((path[i + 1].world - path[i].world).norm(), 1e-9);
    }
    fastest = std::max(fastest, std::sqrt(c.tension() * curvature * invMass));
  }
  return fastest;
}

int MidpointSolver::solve(std::span<const BodyState> bodies, std::span<Cable> cables,
                          std::span<const int> which, const Vec2& gravity, double h, double share,
                          std::span<Vec3> forces, std::span<Vec3> kicks) {
  share_ = share;
  redundant_ = floorHit_ = false;
  iterationsRun_ = 0;
  if (!buildRows(bodies, cables, which, gravity, h, forces)) return 0;
  auto floorPushes = [&] {
    for (size_t r = 0; r < rows_.size(); ++r)
      if (segment_[r] >= 0 && P_[r] > 0) return true;
    return false;
  };
  int pushing = 0;  // iterations in a row on which a floor pushed
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    const bool settled = (++iterationsRun_, newtonStep(bodies, cables, h, iteration == 0));
    if (redundant_) return -1;
    pushing = floorPushes() ? pushing + 1 : 0;
    // A floor that pushes from the start is a body resting at its pulley: given up after
    // kFloorIterations, not after the 15-20 a settled Newton takes (a tackle whose effort rests
    // at its sheave did those on every step, to hand the step over anyway). A push on the first
    // iteration alone can be the linearisation's (a box tied off its centre swinging in).
    const bool fromTheStart = pushing == iteration + 1 && pushing >= kFloorIterations;
    // A point the step takes into a circle's disc (entersRimFloor) is handed over too.
    if ((settled &&
         (pushing > 0 || entersRimFloor(bodies, predicted_, cables, rows_, dofOfBody_))) ||
        fromTheStart) {
      floorHit_ = true;
      return -1;
    }
    if (settled) {
      finish(bodies, cables, h, forces, kicks);
      return iteration + 1;
    }
  }
  return -1;
}

// Rows and dofs as in the main solve; v* moves the bodies half-way in velocity (the position
// step of the midpoint rule), vFree is what Box2D alone would reach.
bool MidpointSolver::buildRows(std::span<const BodyState> bodies, std::span<Cable> cables,
                               std::span<const int> which, const Vec2& gravity, double h,
                               std::span<const Vec3> forces) {
  rows_.clear();
  // Over the world's bodies, but reset only where the last island had dofs: an island's solve
  // costs its own size, not the world's.
  if (dofOfBody_.size() != bodies.size()) {
    dofOfBody_.assign(bodies.size(), -1);
    predicted_.assign(bodies.begin(), bodies.end());
    midpoint_ = predicted_;
  }
  for (const int b : bodyOfDof_) dofOfBody_[b] = -1;
  bodyOfDof_.clear();
  for (const int i : which) {
    bool pulls = false;
    for (const auto& e : cables[i].kinematics().jacobian)
      if (moves(bodies[e.body])) {
        pulls = true;
        if (dofOfBody_[e.body] < 0) {
          dofOfBody_[e.body] = 3 * static_cast<int>(bodyOfDof_.size());
          bodyOfDof_.push_back(e.body);
        }
      }
    if (pulls)
      rows_.push_back(i);
    else
      cables[i].setTension(0);
    // The rows read the poses of the bodies on the paths (q0 where they are not moved).
    for (const WrapPoint& w : cables[i].path())
      if (w.body >= 0) predicted_[w.body] = midpoint_[w.body] = bodies[w.body];
  }
  segment_.assign(rows_.size(), -1);
  normals_.assign(rows_.size(), Vec2::Zero());
  const size_t cableRows = rows_.size();
  for (size_t r = 0; r < cableRows; ++r) {
    const auto& path = cables[rows_[r]].path();
    for (size_t i = 0; i + 1 < path.size(); ++i)
      if (needsFloor(cables[rows_[r]], i, bodies, h, gravity,
                     [&](int b) { return dofOfBody_[b] >= 0; })) {
        rows_.push_back(rows_[r]);
        segment_.push_back(static_cast<int>(i));
        normals_.push_back(floorNormal(path[i], path[i + 1], bodies, h, gravity));
      }
  }
  unresolved_.assign(rows_.size(), 0);
  for (size_t r = 0; r < cableRows; ++r) {
    const Cable& c = cables[rows_[r]];
    unresolved_[r] = c.elastic() && elasticMode(c, bodies) * h > kMaxElasticOmegaH;
  }
  const int m = static_cast<int>(rows_.size()), n = 3 * static_cast<int>(bodyOfDof_.size());
  if (m == 0) return false;
  invM_.resize(n);
  vStar_.resize(n);
  vFree_.resize(n);
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const int body = bodyOfDof_[k];
    const BodyState& s = bodies[body];
    const Vec3 im(s.invMass, s.invMass, s.invInertia);
    Vec3 accel = im.cwiseProduct(forces[body]);
    if (s.invMass > 0) accel.head<2>() += gravity;
    const Vec3 v(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    invM_.segment<3>(3 * k) = im;
    vStar_.segment<3>(3 * k) = v + 0.5 * h * accel;
    vFree_.segment<3>(3 * k) = v + h * accel;
  }
  phi0_.resize(m);
  phi1_.resize(m);
  gradients_.resize(m);
  for (int r = 0; r < m; ++r) {
    const auto& path = cables[rows_[r]].path();
    const int seg = segment_[r];
    phi0_[r] =
        seg < 0 ? cables[rows_[r]].stretch() : kFloorLength - floorGap(path[seg], path[seg + 1]);
  }
  chords_.start(bodies, bodyOfDof_);
  chordPath_.assign(m, -1);
  for (int r = 0; r < m; ++r) {
    const auto& path = cables[rows_[r]].path();
    if (segment_[r] < 0 && std::none_of(path.begin(), path.end(), [](const WrapPoint& w) {
          return w.kind == WrapPoint::Kind::Circle;
        }))
      chordPath_[r] = chords_.addPath(
          path, bodies, [&](int b) { return dofOfBody_[b] >= 0 ? dofOfBody_[b] / 3 : -1; });
  }
  P_.setZero(m);
  vb_ = vStar_;
  K_.resize(m, m);
  b_.resize(m);
  return true;
}

// A = M + h/4 sum_r P_r H_r: the discrete gradient turns with q1 at half J's rate. H_r is the
// length's Hessian in (x, y, theta) at the midpoint pose: per segment B_i^T (I - u u^T) / |d| B_j
// with B = [I | perp(r)] of each end, and u . (-r) on a turning end's theta-theta entry.
void MidpointSolver::buildIterationMatrix(std::span<const Cable> cables, double h) {
  const int n = static_cast<int>(invM_.size());
  blockDiagonal_ = true;
  A_.setZero(n, n);
  for (int d = 0; d < n; ++d) A_(d, d) = invM_[d] > 0 ? 1.0 / invM_[d] : 1.0;
  for (size_t r = 0; r < rows_.size(); ++r) {
    if (P_[r] <= 0 || segment_[r] >= 0) continue;  // floors: their (negative) Hessian left out
    const double scale = 0.25 * h * P_[r];
    std::span<const StepChords::Point> path;
    if (chordPath_[r] >= 0) {
      path = chords_.points(chordPath_[r]);
    } else {
      midPoints_.clear();
      for (const WrapPoint& w : cables[rows_[r]].path())
        midPoints_.push_back({w.body, -1, w.local, w.world, Vec2::Zero(), w.world,
                              worldPoint(midpoint_, w.body, w.local), Vec2::Zero()});
      path = midPoints_;
    }
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      const StepChords::Point* ends[2] = {&path[i], &path[i + 1]};
      if (ends[0]->body == ends[1]->body) continue;
      const Vec2 d = ends[1]->mid - ends[0]->mid;
      const double len = d.norm();
      if (len < 1e-12) continue;
      const Vec2 u = d / len;
      const Eigen::Matrix2d hs = (Eigen::Matrix2d::Identity() - u * u.transpose()) / len;
      Eigen::Matrix<double, 2, 3> B[2];
      int dof[2];
      for (int e = 0; e < 2; ++e) {
        const int body = ends[e]->body;
        dof[e] = body >= 0 ? dofOfBody_[body] : -1;
        const Vec2 arm = body >= 0 ? Vec2(ends[e]->mid - midpoint_[body].position) : Vec2::Zero();
        B[e] << 1, 0, perp(arm).x(), 0, 1, perp(arm).y();
        if (e == 0) B[e] = -B[e];
        if (dof[e] >= 0) A_(dof[e] + 2, dof[e] + 2) += scale * (e == 0 ? 1 : -1) * u.dot(arm);
      }
      if (dof[0] >= 0 && dof[1] >= 0) blockDiagonal_ = false;
      for (int e = 0; e < 2; ++e)
        for (int f = 0; f < 2; ++f)
          if (dof[e] >= 0 && dof[f] >= 0)
            A_.block<3, 3>(dof[e], dof[f]) += scale * B[e].transpose() * hs * B[f];
    }
  }
  for (int d = 0; d < n; ++d)
    if (invM_[d] == 0) {
      A_.row(d).setZero();
      A_.col(d).setZero();
      A_(d, d) = 1;
    }
  if (blockDiagonal_)
    blockInverse_.compute(A_);
  else
    ldlt_.compute(A_);
}

// One Newton step on (v_b, P): A dv + G^T dP / 2 = -R, R = M (v_b - v*) + G^T P / 2, with the
// rows' conditions linearised in P (an LCP: rigid cables may go slack). True once settled.
bool MidpointSolver::newtonStep(std::span<const BodyState> bodies, std::span<const Cable> cables,
                                double h, bool first) {
  const int m = static_cast<int>(rows_.size()), n = static_cast<int>(invM_.size());
  evaluate(bodies, cables, h);
  buildIterationMatrix(cables, h);
  Gt_.setZero(n, m);
  for (int r = 0; r < m; ++r)
    for (const auto& e : gradients_[r])
      if (const int d = dofOfBody_[e.body]; d >= 0) Gt_.block<3, 1>(d, r) = e.d;
  for (int d = 0; d < n; ++d)
    if (invM_[d] == 0) Gt_.row(d).setZero();
  residual_.resize(n);
  for (int d = 0; d < n; ++d) residual_[d] = invM_[d] > 0 ? (vb_[d] - vStar_[d]) / invM_[d] : 0;
  // Small islands (an Atwood machine: one row, six dofs) take coefficient-based products: Eigen's
  // blocked kernels cost more to dispatch than these few products (docs/performance.md).
  const bool small = m * n <= kLazyProductSize;
  if (small)
    residual_.noalias() += 0.5 * Gt_.lazyProduct(P_);
  else
    residual_.noalias() += 0.5 * Gt_ * P_;
  if (blockDiagonal_) {
    blockInverse_.solve(Gt_, AinvGt_);
    blockInverse_.solve(residual_, AinvR_);
  } else {
    AinvGt_ = ldlt_.solve(Gt_);
    AinvR_ = ldlt_.solve(residual_);
  }
  if (small) {
    K_.noalias() = 0.5 * Gt_.transpose().lazyProduct(AinvGt_);
    GAinvR_.noalias() = Gt_.transpose().lazyProduct(AinvR_);
  } else {
    K_.noalias() = 0.5 * Gt_.transpose() * AinvGt_;
    GAinvR_.noalias() = Gt_.transpose() * AinvR_;
  }
  for (int r = 0; r < m; ++r) {
    const Cable& c = cables[rows_[r]];
    const double kp = K_.row(r).dot(P_) - GAinvR_[r];
    if (!c.elastic() || segment_[r] >= 0) {
      b_[r] = kp + (phi1_[r] - rigidTarget(phi0_[r], share_)) / h;
      continue;
    }
    // P / h = the secant tension (+ damping) at the new phi1, linearised.
    const double k = c.parameters().stiffness, damp = c.parameters().damping;
    const SpringSecant sec =
        unresolved_[r] ? springAtEnd(k, phi1_[r]) : springSecant(k, phi0_[r], phi1_[r]);
    const double tension = sec.tension + damp * (phi1_[r] - phi0_[r]) / h;
    const double slope = std::max(sec.slope + damp / h, 1e-12 * (k + damp / h));
    K_(r, r) += 1.0 / (slope * h * h);
    b_[r] = kp + tension / (slope * h);
  }
  solveLcp(K_, b_, lcp_, solution_);
  // Redundant rows that pull (the floors of a tackle's four falls, all closed: K singular on
  // them) leave the split of their impulses free, and Newton on P then never settles: such an
  // island goes to the main solve, which takes the minimum-norm split (docs/model.md,
  // "Redundant cables").
  redundant_ = first && redundantActiveRows(cables);
  if (redundant_) return false;
  dP_ = solution_.x - P_;
  if (small)
    dv_.noalias() = 0.5 * AinvGt_.lazyProduct(dP_);  // into dv_ first: no temporary
  else
    dv_.noalias() = 0.5 * AinvGt_ * dP_;
  dv_ = -(AinvR_ + dv_);
  P_ = solution_.x;
  vb_ += dv_;
  const double moved = h * dv_.lpNorm<Eigen::Infinity>(), changed = dP_.lpNorm<Eigen::Infinity>();
  const double impulseTolerance = 1e-9 * (1e-9 + P_.lpNorm<Eigen::Infinity>());
  // Settled where this correction is within the tolerances, or where the next one will be: the
  // corrections shrink by a steady factor (the iteration matrix is not the discrete gradient's
  // exact derivative; a swinging Atwood machine's by 1e-5..1e-2 an iteration), so the next is
  // about this one times its ratio to the last. Taken only at a ratio of 0.1 or less, where the
  // rest of the series is within 1.1 times that next one. The iteration that would only confirm
  // it is then not run (a full one, a quarter of such a machine's solve; docs/performance.md).
  const bool settles = moved <= kPositionTolerance && changed <= impulseTolerance;
  const bool nextSettles = !first && moved <= 0.1 * lastMoved_ && changed <= 0.1 * lastChanged_ &&
                           moved * moved <= kPositionTolerance * lastMoved_ &&
                           changed * changed <= impulseTolerance * lastChanged_;
  lastMoved_ = moved;
  lastChanged_ = changed;
  return settles || nextSettles;
}

// Whether the rigid rows the LCP's solution pulls on are dependent (K singular on them). An
// elastic row's spring sets its share of the load whatever the others do, so it is never
// redundant; counted, a row coming taut (its secant slope near nil, its compliance huge) made
// every other pivot look nil beside its own, and four stiff cables on one platform went to the
// main solve's damping spring (tests/engine/dynamics/stiff_elastic_test.cpp).
bool MidpointSolver::redundantActiveRows(std::span<const Cable> cables) {
  active_.clear();
  for (int r = 0; r < static_cast<int>(solution_.x.size()); ++r)
    if (solution_.x[r] > 0 && (segment_[r] >= 0 || !cables[rows_[r]].elastic()))
      active_.push_back(r);
  const int a = static_cast<int>(active_.size());
  if (a < 2) return false;
  activeK_.resize(a, a);
  for (int i = 0; i < a; ++i)
    for (int j = 0; j < a; ++j) activeK_(i, j) = K_(active_[i], active_[j]);
  redundancy_.compute(activeK_);
  return rankDeficient(redundancy_);
}

// The midpoint rule holds a rigid cable's length, q1 = q0 + h (v0 + v1) / 2, which fixes the
// sum v0 + v1 along the cable and leaves their difference free: a rate J v0 at the start comes
// back as -J v1 at the end, step after step, and the tension alternates with it (a bob whose rope
// wrapped a peg at 240 Hz: +-20% about the right tension for as long as it swung; a platform at
// rest on rigid cables: a velocity of 1-2 mm/s with its pose frozen). A pulling rigid row's end
// rate J1 v1 is therefore held to no more than the mean of its start and end rates (J0 v0 + J1 v1)
// / 2 by an impulse mu >= 0 at the end of the step (RATTLE's velocity step, docs/cables.md,
// "Energy"). On the smooth motion the two rates agree to O(h^3) and mu is nil; the alternation
// dies within two steps. The kinetic energy mu moves round fixed pegs is put back
// (settled_energy.h: up to 1e-5 J a step round a polygon peg at 30 Hz, summed into a steady
// leak). Into v1_ (the end velocities) and mu_.
void MidpointSolver::settleRates(std::span<const BodyState> bodies, std::span<const Cable> cables) {
  const int n = static_cast<int>(invM_.size());
  v1_.resize(n);
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const BodyState& s = bodies[bodyOfDof_[k]];
    const Vec3 v0(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    v1_.segment<3>(3 * k) = 2 * vb_.segment<3>(3 * k) - v0;
  }
  settled_.clear();
  for (size_t r = 0; r < rows_.size(); ++r)
    if (segment_[r] < 0 && P_[r] > 0 && !cables[rows_[r]].elastic())
      settled_.push_back(static_cast<int>(r));
  mu_.setZero(static_cast<Eigen::Index>(rows_.size()));
  endShift_.setZero(n);
  const int s = static_cast<int>(settled_.size());
  if (s == 0) return;
  endW_.setZero(n, s);
  endJ_.resize(s, n);
  rateB_.resize(s);
  for (int i = 0; i < s; ++i) {
    const Cable& c = cables[rows_[settled_[i]]];
    double start = 0, end = 0;
    for (const auto& e : c.kinematics().jacobian) {  // J0 v0
      const BodyState& b = bodies[e.body];
      start += e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
    }
    if (const int held = chordPath_[settled_[i]]; held >= 0) {
      chords_.endJacobian(held, predicted_, kin_.jacobian);
    } else {
      path_.assign(c.path().begin(), c.path().end());
      cableLengthJacobian(path_, predicted_, kin_);
    }
    for (const auto& e : kin_.jacobian)
      if (const int d = dofOfBody_[e.body]; d >= 0) {
        endW_.block<3, 1>(d, i) = invM_.segment<3>(d).cwiseProduct(e.d);
        end += e.d.dot(v1_.segment<3>(d));
      } else {
        const BodyState& b = bodies[e.body];
        end += e.d.dot(Vec3(b.velocity.x(), b.velocity.y(), b.angularVelocity));
      }
    rateB_[i] = 0.5 * (end - start);  // w = K mu - (J1 v1 - (J0 v0 + J1 v1) / 2) >= 0
    endJ_.row(i).setZero();
    for (const auto& e : kin_.jacobian)
      if (const int d = dofOfBody_[e.body]; d >= 0) endJ_.block<1, 3>(i, d) += e.d.transpose();
  }
  if (!(rateB_.maxCoeff() > 0)) return;
  rateK_.noalias() = endJ_ * endW_;
  solveLcp(rateK_, rateB_, lcp_, solution_, true);
  endShift_.noalias() = endW_ * solution_.x;
  const double before = kineticEnergyOfShifted(v1_, endShift_, invM_);
  v1_ -= endShift_;
  // Put back on islands of rigid ropes round fixed pegs, those it acts on taut for
  // kSettledTautSteps (a swing's alternation, not a catch). Not where a rope runs over free
  // pulleys: polygons in rope loops left their ropes (KnockMotion.PolygonsWedged*,
  // FreePulleyContacts.PolygonsInLoopsUnderASwingingBob*).
  bool swings = true;
  for (int i = 0; i < s; ++i) {
    mu_[settled_[i]] = solution_.x[i];
    swings = swings && (solution_.x[i] == 0 || settledTaut(rows_[settled_[i]]));
  }
  for (size_t r = 0; r < rows_.size() && swings; ++r)
    swings = segment_[r] >= 0 || fixedBetweenEnds(bodies, cables, {&rows_[r], 1});
  if (swings) keepSettledEnergy(v1_, endShift_, invM_, before);
}

// Tensions (each row's impulse over the step, the end one included, over h), the force that
// gives Box2D the velocity v_b, and the rest after its step: the end velocities themselves,
// which World sets (appendEnds), and as kicks for a body it cannot set.
void MidpointSolver::finish(std::span<const BodyState> bodies, std::span<Cable> cables, double h,
                            std::span<Vec3> forces, std::span<Vec3> kicks) {
  settleRates(bodies, cables);
  for (size_t r = 0; r < rows_.size(); ++r)
    if (segment_[r] < 0) cables[rows_[r]].setTension((P_[r] + mu_[r]) / h);
  for (size_t k = 0; k < bodyOfDof_.size(); ++k) {
    const int body = bodyOfDof_[k];
    const BodyState& s = bodies[body];
    const Vec3 v0(s.velocity.x(), s.velocity.y(), s.angularVelocity);
    for (int c = 0; c < 3; ++c) {
      const int d = 3 * static_cast<int>(k) + c;
      if (invM_[d] == 0) continue;
      forces[body][c] += (vb_[d] - vFree_[d]) / (h * invM_[d]);
      kicks[body][c] = vb_[d] - v0[c] - endShift_[d];
    }
  }
}

void MidpointSolver::appendEnds(std::vector<std::pair<int, Vec3>>& ends) const {
  for (size_t k = 0; k < bodyOfDof_.size(); ++k)
    ends.emplace_back(bodyOfDof_[k], v1_.segment<3>(3 * k));
}

}  // namespace cablelab
