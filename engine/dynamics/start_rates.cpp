// Start rates matched to the step's rule (rationale in start_rates.h).
#include "engine/dynamics/start_rates.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "engine/dynamics/floors.h"

namespace cablelab {

namespace {

// A rate further than this share of a whole sub-step's chord rate, (h / 2) L'', from the one the
// last step left is no artefact of it (a cable coming slack, a knock): left to the solve. Not
// less than one: across a wrap change L'' jumps (a rope wrapping a peg 0.6 m down its 1 m: x 2.5)
// and the rate left is the old path's.
constexpr double kArtefactShare = 1.0;

// Midpoint steps whose lengths differ by more than this ratio keep their rate (the fast-catch
// refinement's equal parts differ by 2-3 from the whole step near a peg at 20 Hz).
constexpr double kMaxMidpointStepRatio = 4;

// A segment shorter than this many sub-steps of its ends' closing motion, plus kFloorMargin of
// its floor's length: its end may reach its pulley (floors.h) within them.
constexpr double kFloorReach = 4;
constexpr double kFloorMargin = 5;

bool nearingFloor(const WrapPoint& p, const WrapPoint& q, std::span<const BodyState> bodies,
                  double h) {
  const Vec2 d = q.arriving() - p.leaving();
  const double gap = d.norm();
  const double closing = gap > 0 ? -d.dot(floorDrift(p, q, bodies, h, Vec2::Zero())) / gap : 0;
  return gap < kFloorReach * std::max(closing, 0.0) + kFloorMargin * kFloorLength;
}

struct PathPointMotion {
  Vec2 position, velocity, acceleration;
};

// Whether path point w stays where it is over the step: on the world, or on a body that neither
// the solve nor a drive moves (a static body, a kinematic one at rest: a peg a scene places as a
// body of its own is as fixed as one on the world).
bool fixedInWorld(const WrapPoint& w, std::span<const BodyState> bodies) {
  return w.body < 0 || (!moves(bodies[w.body]) && !driven(bodies[w.body]));
}

// A path point where segment i meets it (`out`: the segment leaves it), moving with its body at
// constant velocity. Nothing if it is a circle on a moving body (its tangent point slides).
bool pathPointMotion(const WrapPoint& w, bool out, std::span<const BodyState> bodies,
                     PathPointMotion& p) {
  if (w.kind == WrapPoint::Kind::Circle) {
    if (!fixedInWorld(w, bodies)) return false;
    p = {out ? w.tangentOut : w.tangentIn, Vec2::Zero(), Vec2::Zero()};
    return true;
  }
  if (w.body < 0) {
    p = {w.world, Vec2::Zero(), Vec2::Zero()};
    return true;
  }
  const BodyState& b = bodies[w.body];
  const Vec2 arm = w.world - b.position;
  p = {w.world, pointVelocity(b, w.world), Vec2(-b.angularVelocity * b.angularVelocity * arm)};
  return true;
}

// The second derivative of the cable's length along the bodies' motion at their velocities now
// (its wrap set fixed): per segment the square of its ends' velocity across it over its length,
// plus their turning accelerations along it. False where a point cannot say (pathPointMotion).
bool lengthCurvature(const Cable& c, std::span<const BodyState> bodies, double& second) {
  const auto& path = c.path();
  second = 0;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    if (path[i].body == path[i + 1].body && path[i].radius == path[i + 1].radius) continue;
    PathPointMotion p, q;
    if (!pathPointMotion(path[i], true, bodies, p) ||
        !pathPointMotion(path[i + 1], false, bodies, q))
      return false;
    const Vec2 d = q.position - p.position;
    const double length = d.norm();
    if (!(length > 1e-9)) continue;
    const Vec2 u = d / length, rate = q.velocity - p.velocity;
    const double along = u.dot(rate);
    second += (rate.squaredNorm() - along * along) / length +
              u.dot(Vec2(q.acceleration - p.acceleration));
  }
  return true;
}

Vec3 velocityOf(const BodyState& b) {
  return {b.velocity.x(), b.velocity.y(), b.angularVelocity};
}

double kineticEnergy(std::span<const int> which, std::span<const BodyState> bodies) {
  double e = 0;
  for (const int b : which) e += kineticEnergy(bodies[b]);
  return e;
}

}  // namespace

std::vector<int> matchStartRates(const StartRateInput& in, std::vector<BodyState>& bodies) {
  std::vector<int> rows, changed;
  std::vector<double> miss;  // per row: its rate less the one its next step ends on
  for (size_t c = 0; c < in.cables.size(); ++c) {
    const Cable& cable = in.cables[c];
    const double last = in.lastSteps[c], next = in.nextSteps[c];
    // Midpoint to midpoint: the lengths of the two steps (start_rates.h).
    const double lastMidpoint =
        last == 0 && next == 0 && c < in.lastMidpointSteps.size() ? in.lastMidpointSteps[c] : 0.0;
    // Not across a cut at a wrap event: a piece far shorter than its neighbour ends on a rate its
    // own length says little of (the new path's), and scaled up it would be a knock.
    const bool midpoint =
        lastMidpoint > 0 && std::abs(lastMidpoint - in.step) > 1e-9 * in.h &&
        std::max(lastMidpoint, in.step) <= kMaxMidpointStepRatio * std::min(lastMidpoint, in.step);
    if (cable.elastic() || cable.spanCount() != 1 || !(cable.tension() > 0) || last < 0 ||
        next < 0 || (!midpoint && std::abs(last - next) <= 1e-9 * in.h))
      continue;
    bool alone = true;
    double rate = 0;
    for (const auto& e : cable.kinematics().jacobian) {
      const BodyState& b = bodies[e.body];
      if (moves(b))
        alone &= !in.excluded[e.body] && e.body != in.dragBody && b.invMass > 0;
      else
        alone &= !driven(b);
      rate += e.d.dot(velocityOf(b));
    }
    // Points between the ends on moving bodies (free polygons in rope loops, pulleys on arms)
    // and ends nearing their pulleys (floors.h) are left to the solve: there the rate is the
    // knock's or the floor's as much as the step's.
    const auto& path = cable.path();
    for (size_t i = 0; alone && i + 1 < path.size(); ++i)
      alone =
          (i == 0 || fixedInWorld(path[i], bodies)) &&
          (path[i].body == path[i + 1].body || !nearingFloor(path[i], path[i + 1], bodies, in.h));
    double second = 0;
    if (!alone || !lengthCurvature(cable, bodies, second)) continue;
    if (!(std::abs(rate - 0.5 * last * second) <= kArtefactShare * 0.5 * in.h * std::abs(second)))
      continue;
    rows.push_back(static_cast<int>(c));
    const double ratio = midpoint ? in.step / lastMidpoint : 0.0;
    miss.push_back(midpoint ? rate * (1 - ratio * ratio) : rate - 0.5 * next * second);
  }
  const int m = static_cast<int>(rows.size());
  if (m == 0) return changed;
  // lambda: K lambda = miss, K = J M^-1 J^T; the velocities move by -M^-1 J^T lambda.
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m, m);
  auto invMass = [&](int b) {
    const BodyState& s = bodies[b];
    return Vec3(s.invMass, s.invMass, s.invInertia);
  };
  for (int i = 0; i < m; ++i)
    for (const auto& a : in.cables[rows[i]].kinematics().jacobian)
      for (int j = 0; j < m; ++j)
        for (const auto& e : in.cables[rows[j]].kinematics().jacobian)
          if (a.body == e.body) K(i, j) += a.d.dot(invMass(a.body).cwiseProduct(e.d));
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(K);
  const Eigen::VectorXd pivots = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > 1e-9 * pivots.maxCoeff()))
    return changed;  // dependent rows: no unique way to turn them
  const Eigen::VectorXd lambda = ldlt.solve(Eigen::Map<const Eigen::VectorXd>(miss.data(), m));
  for (int i = 0; i < m; ++i)
    for (const auto& e : in.cables[rows[i]].kinematics().jacobian)
      if (moves(bodies[e.body]) &&
          std::find(changed.begin(), changed.end(), e.body) == changed.end())
        changed.push_back(e.body);
  const double before = kineticEnergy(changed, bodies);
  for (int i = 0; i < m; ++i)
    for (const auto& e : in.cables[rows[i]].kinematics().jacobian) {
      BodyState& b = bodies[e.body];
      if (!moves(b)) continue;
      const Vec3 dv = -lambda[i] * invMass(e.body).cwiseProduct(e.d);
      b.velocity += dv.head<2>();
      b.angularVelocity += dv.z();
    }
  // The rate's energy goes into the motion across the cables: the kinetic energy is kept.
  const double after = kineticEnergy(changed, bodies);
  if (after > 0 && before > 0) {
    const double scale = std::sqrt(before / after);
    for (const int b : changed) {
      bodies[b].velocity *= scale;
      bodies[b].angularVelocity *= scale;
    }
  }
  return changed;
}

void recordStartRateSteps(std::span<const Cable> cables, std::span<const char> midpoint, double dt,
                          std::vector<double>& steps, std::vector<double>& midpointSteps) {
  steps.assign(cables.size(), kNoStartRate);
  midpointSteps.assign(cables.size(), 0.0);
  for (size_t c = 0; c < cables.size(); ++c) {
    const Cable& cable = cables[c];
    if (cable.elastic() || cable.spanCount() != 1 || !(cable.tension() > 0)) continue;
    steps[c] = !midpoint.empty() && midpoint[c] ? 0.0 : dt;
    if (steps[c] == 0) midpointSteps[c] = dt;
  }
}

}  // namespace cablelab
