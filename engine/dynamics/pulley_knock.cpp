#include "engine/dynamics/pulley_knock.h"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>

namespace cablelab {

namespace {

// m: a rigid rope no shorter than its rest length by more than this is taut: it takes part in a
// knock (its rate is about zero and stays so). A slacker one cannot pass an impulse on.
constexpr double kTautWithin = 1e-4;
// How the time a pair comes within the skin is looked for over the horizon: sampled, then halved.
constexpr int kAheadSamples = 8;
constexpr int kAheadHalvings = 5;

std::vector<Vec2> hullAtPose(const BodyState& b, const std::vector<Vec2>& local) {
  std::vector<Vec2> out;
  out.reserve(local.size());
  for (const Vec2& v : local) out.push_back(b.position + rotate(v, b.angle));
  return out;
}

// The nearest points of two convex hulls that do not overlap: a vertex of one and the nearest
// point of an edge of the other. Returns the gap (m).
double nearestHullPoints(const std::vector<Vec2>& a, const std::vector<Vec2>& b, Vec2& onA,
                         Vec2& onB) {
  double best = std::numeric_limits<double>::infinity();
  auto vertexToEdges = [&](const std::vector<Vec2>& vertices, const std::vector<Vec2>& edges,
                           bool vertexOnA) {
    for (const Vec2& p : vertices)
      for (size_t i = 0; i < edges.size(); ++i) {
        const Vec2 s = edges[i], edge = edges[(i + 1) % edges.size()] - s;
        const double along = std::clamp((p - s).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
        const Vec2 q = s + along * edge;
        const double d = (p - q).norm();
        if (d >= best) continue;
        best = d;
        onA = vertexOnA ? p : q;
        onB = vertexOnA ? q : p;
      }
  };
  vertexToEdges(a, b, true);
  vertexToEdges(b, a, false);
  return best;
}

// `b` moved on t s at its present velocities.
BodyState ahead(const BodyState& b, double t) {
  BodyState out = b;
  out.position += t * b.velocity;
  out.angle += t * b.angularVelocity;
  return out;
}

double rowRate(const std::vector<std::pair<int, Vec3>>& entries,
               const std::vector<BodyState>& bodies) {
  double rate = 0;
  for (const auto& [body, d] : entries) {
    const BodyState& s = bodies[body];
    rate += d.x() * s.velocity.x() + d.y() * s.velocity.y() + d.z() * s.angularVelocity;
  }
  return rate;
}

}  // namespace

PulleyKnock::PulleyKnock(const SceneDef& scene, const std::vector<HullContact>& contacts)
    : responses_(knockResponses(scene)) {
  for (const HullContact& c : contacts) {
    if (c.otherPolygon.empty() || c.body < 0 || c.otherBody < 0) continue;
    if (scene.bodies[c.body].type != BodyType::Dynamic ||
        scene.bodies[c.otherBody].type != BodyType::Dynamic)
      continue;
    const double e =
        std::max(largestRestitution(scene, c.body), largestRestitution(scene, c.otherBody));
    if (!(e > 0)) continue;
    pairs_.push_back({c.body, c.otherBody, c.polygon, c.otherPolygon, std::min(e, 1.0), false});
  }
}

bool PulleyKnock::knocks(int a, int b) const {
  if (a < 0 || b < 0 || !responses_[a].known || !responses_[b].known) return false;
  return std::any_of(pairs_.begin(), pairs_.end(), [&](const Pair& p) {
    return (p.bodyA == a && p.bodyB == b) || (p.bodyA == b && p.bodyB == a);
  });
}

Vec3 PulleyKnock::response(const BodyState& b, int body, const Vec3& w) const {
  if (!responses_[body].pivoted)
    return Vec3(b.invMass * w.x(), b.invMass * w.y(), b.invInertia * w.z());
  if (!(b.invMass > 0) || !(b.invInertia > 0)) return Vec3::Zero();  // held still by its pivot
  // Turning about the pivot p: the origin moves at omega perp(x - p); the moment about p is
  // I + m |x - p|^2 (parallel axes).
  const Vec2 arm = -rotate(responses_[body].pivot, b.angle);
  const Vec3 u(perp(arm).x(), perp(arm).y(), 1.0);
  const double inverseMoment =
      1 / (1 / b.invInertia + responses_[body].pivot.squaredNorm() / b.invMass);
  return inverseMoment * u.dot(w) * u;
}

bool PulleyKnock::solveAndApply(std::vector<Row>& rows, std::vector<BodyState>& bodies,
                                std::vector<int>& changed) const {
  // Row 0 is the contact; the rest ropes, dropped while they would push.
  std::vector<int> active(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) active[i] = static_cast<int>(i);
  Eigen::VectorXd impulse;
  for (;;) {
    const int n = static_cast<int>(active.size());
    Eigen::MatrixXd k(n, n);
    Eigen::VectorXd rhs(n);
    for (int j = 0; j < n; ++j) {
      const Row& rj = rows[active[j]];
      rhs(j) = rj.target - rj.rate;
      for (int i = 0; i < n; ++i) {
        double kij = 0;
        for (const auto& [bi, di] : rows[active[i]].entries)
          for (const auto& [bj, dj] : rj.entries)
            if (bi == bj) kij += di.dot(response(bodies[bi], bi, dj));
        k(i, j) = kij;
      }
    }
    impulse = k.completeOrthogonalDecomposition().solve(rhs);
    if (!(impulse(0) > 0) || !impulse.allFinite()) return false;
    int worst = -1;
    for (int i = 1; i < n; ++i)
      if (impulse(i) < 0 && (worst < 0 || impulse(i) < impulse(worst))) worst = i;
    if (worst < 0) break;
    active.erase(active.begin() + worst);
  }
  std::vector<std::pair<int, Vec3>> wrench;
  for (size_t i = 0; i < active.size(); ++i)
    for (const auto& [body, d] : rows[active[i]].entries) {
      auto it = std::find_if(wrench.begin(), wrench.end(),
                             [body = body](const auto& w) { return w.first == body; });
      if (it == wrench.end()) it = wrench.insert(wrench.end(), {body, Vec3::Zero()});
      it->second += impulse(static_cast<int>(i)) * d;
    }
  for (const auto& [body, w] : wrench) {
    BodyState& b = bodies[body];
    const Vec3 dv = response(b, body, w);
    b.velocity += dv.head<2>();
    b.angularVelocity += dv.z();
    changed.push_back(body);
  }
  return true;
}

std::vector<int> PulleyKnock::knock(std::vector<BodyState>& bodies, std::span<const Cable> cables,
                                    double horizon, double skin) {
  std::vector<int> changed;
  // A knock turns its bodies, which may bring another pair in, or the same pair closing at another
  // corner within the horizon (meshed polygons pinned a few mm apart).
  constexpr int kPasses = 16;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool any = false;
    for (Pair& p : pairs_) {
      if (!responses_[p.bodyA].known || !responses_[p.bodyB].known) continue;
      const BodyState &a = bodies[p.bodyA], &b = bodies[p.bodyB];
      // The hulls' gap (m; < 0 overlapping) t s ahead at the present velocities.
      Vec2 onA = Vec2::Zero(), onB = Vec2::Zero();
      auto gapAhead = [&](double t) {
        const std::vector<Vec2> hullA = hullAtPose(ahead(a, t), p.polygonA),
                                hullB = hullAtPose(ahead(b, t), p.polygonB);
        if (hullsOverlap(hullA, hullB)) return -1.0;
        return nearestHullPoints(hullA, hullB, onA, onB);
      };
      const double gap = gapAhead(0);
      if (!(gap > 0)) continue;  // overlapping: Box2D's contact pushes them apart
      // Pinned at their pivots, a pair placed within the skin (apart) cannot be resting on each
      // other: knocked at once, not by Box2D's contact (docs/knocks.md, "Two pulleys knocking").
      p.armed |= gap > skin || (responses_[p.bodyA].pivoted && responses_[p.bodyB].pivoted);
      if (!p.armed) continue;
      // The contact row at the nearest points t s ahead (its rate at the present velocities).
      auto contactAhead = [&](double t, Row& row) {
        const double gapThen = gapAhead(t);
        if (!(gapThen > 0) || gapThen > skin) return false;
        const Vec2 normal = (onB - onA) / gapThen;  // from A to B
        const Vec2 centreA = ahead(a, t).position, centreB = ahead(b, t).position;
        row.entries = {{p.bodyA, Vec3(-normal.x(), -normal.y(), -cross(onA - centreA, normal))},
                       {p.bodyB, Vec3(normal.x(), normal.y(), cross(onB - centreB, normal))}};
        row.rate = rowRate(row.entries, bodies);
        return true;
      };
      // Where they first come within the skin approaching: a corner turning in may meet the other
      // hull away from the nearest points of the present pose, and a pair within the skin but
      // parting there may still close elsewhere within the horizon: left to Box2D, whose knock
      // leaves the pivots out, such a closing loses spin energy (docs/knocks.md, "Two pulleys
      // knocking").
      // Sampled, then halved down to 1/256 of it.
      Row contact;
      auto approaching = [&](double t) { return contactAhead(t, contact) && contact.rate < 0; };
      double before = 0, at = -1;
      if (approaching(0)) at = 0;
      for (int k = 1; k <= kAheadSamples && at < 0; ++k) {
        const double t = horizon * k / kAheadSamples;
        if (approaching(t)) at = t;
        if (at < 0) before = t;
      }
      if (at < 0) continue;
      for (int k = 0; k < kAheadHalvings && at > 0; ++k) {
        const double mid = 0.5 * (before + at);
        (approaching(mid) ? at : before) = mid;
      }
      if (!approaching(at)) continue;
      contact.target = -p.restitution * contact.rate;
      std::vector<Row> rows{contact};
      bool handled = true;
      for (const Cable& c : cables) {
        if (c.elastic() || c.spanCount() != 1 || c.stretch() < -kTautWithin) continue;
        const auto& jacobian = c.kinematics().jacobian;
        const bool on = std::any_of(jacobian.begin(), jacobian.end(), [&](const BodyJacobian& e) {
          return e.body == p.bodyA || e.body == p.bodyB;
        });
        if (!on) continue;
        Row rope;  // its shortening rate: the tension's impulse is >= 0
        for (const BodyJacobian& e : jacobian) {
          handled &= responses_[e.body].known;
          rope.entries.emplace_back(e.body, -e.d);
        }
        rope.rate = rowRate(rope.entries, bodies);
        rope.target = -rope.rate;
        rows.push_back(std::move(rope));
      }
      if (!handled) continue;
      any |= solveAndApply(rows, bodies, changed);
    }
    if (!any) break;
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

}  // namespace cablelab
