// Length, Jacobian and J-dot-v of a cable path (thesis section 2.3 as corrected in
// docs/model.md#cable-geometry, generalised to circles in docs/wheels.md).
//
// Every path point is a circle with centre C (fixed on a body) and signed radius rho (0 for
// anchors, points and polygon vertices). Segment i runs tangent to circles i and i+1 with unit u,
// left normal n and length l; D = C_{i+1} - C_i = l u + (rho_i - rho_{i+1}) n. With W = dD/dt:
//   dl/dt + (arc terms)   = u . W              (the arcs absorb the turn of u, docs/wheels.md)
//   d(u . W)/dt           = u . dW/dt + (|W|^2 - (u . W)^2) / l
// so J and J-dot-v are those of radius-zero points at the centres, with u the tangent's direction.
// A centre fixed on body b at world offset r moves with v_b + omega perp(r); its d/d(x, y, theta)
// is [I | perp(r)] and its velocity-product acceleration is -omega^2 r. A circle at a path's end
// (a drum, or a wheel the cable does not slip on) adds the arc to its material mark: -rho (end)
// or +rho (start) times the body's turn rate.
#include <algorithm>
#include <cmath>

#include "engine/cable/cable.h"
#include "engine/cable/circle_wrap.h"

namespace cablelab {

namespace {

constexpr double kZeroLength = 1e-12;  // m; shorter segments have no direction

struct PointMotion {
  Vec2 offset = Vec2::Zero();    // world offset from the body origin
  Vec2 velocity = Vec2::Zero();  // world velocity of the point
  Vec2 accel = Vec2::Zero();     // -omega^2 r: the J-dot-v part of its acceleration
};

// World points of a path: a path visits few bodies, most of them at several points (polygon
// vertices, both ends on one paddle), so each body's cos/sin is worked out once per call.
class PathFrames {
 public:
  explicit PathFrames(std::span<const BodyState> bodies) : bodies_(bodies) {}

  Vec2 worldPoint(int body, const Vec2& local) {
    if (body < 0) return local;
    const Rotation& r = rotationOf(body);
    return bodies_[body].position + rotate(local, r.c, r.s);
  }

 private:
  struct Rotation {
    int body;
    double c, s;
  };
  const Rotation& rotationOf(int body) {
    for (int i = 0; i < count_; ++i)
      if (cache_[i].body == body) return cache_[i];
    const double angle = bodies_[body].angle;
    Rotation r{body, std::cos(angle), std::sin(angle)};
    if (count_ == kSize) count_ = 0;  // many bodies: recycle the slots
    cache_[count_] = r;
    return cache_[count_++];
  }
  static constexpr int kSize = 4;
  std::span<const BodyState> bodies_;
  Rotation cache_[kSize];
  int count_ = 0;
};

PointMotion motionOf(std::span<const BodyState> bodies, const WrapPoint& p) {
  PointMotion m;
  if (p.body < 0) return m;
  const BodyState& b = bodies[p.body];
  m.offset = p.world - b.position;
  m.velocity = b.velocity + b.angularVelocity * perp(m.offset);
  m.accel = -b.angularVelocity * b.angularVelocity * m.offset;
  return m;
}

void addJacobian(std::vector<BodyJacobian>& jac, int body, const Vec3& d) {
  if (body < 0) return;
  for (auto& e : jac)
    if (e.body == body) {
      e.d += d;
      return;
    }
  jac.push_back({body, d});
}

double bodyAngle(std::span<const BodyState> bodies, int body) {
  return body < 0 ? 0.0 : bodies[body].angle;
}

// The arc lengths on the circles, given every segment's direction (tangents already set).
void addArcs(std::span<WrapPoint> path, std::span<const BodyState> bodies, std::span<const Vec2> u,
             CableKinematics& k) {
  const size_t n = path.size();
  for (size_t i = 0; i < n; ++i) {
    WrapPoint& p = path[i];
    if (p.radius == 0) continue;
    const double rho = p.radius;
    if (i == 0 || i + 1 == n) {
      // A path's end on a circle: the cable is fixed to the mark (a drum or a non-slip wheel).
      const double mark = bodyAngle(bodies, p.body) + p.mark;
      p.arc = i == 0 ? arcFromMark(u[0], rho, mark, p.arc) : arcToMark(u[n - 2], rho, mark, p.arc);
      const double sign = i == 0 ? 1.0 : -1.0;
      if (p.body >= 0) {
        addJacobian(k.jacobian, p.body, Vec3(0, 0, sign * rho));
        k.lengthRate += sign * rho * bodies[p.body].angularVelocity;
      }
    } else {
      p.arc = turnAngle(u[i - 1], u[i], rho, p.arc);
    }
    k.length += std::abs(rho) * p.arc;
  }
}

}  // namespace

Vec2 worldPoint(std::span<const BodyState> bodies, int body, const Vec2& local) {
  if (body < 0) return local;
  const BodyState& b = bodies[body];
  return b.position + rotate(local, b.angle);
}

CableKinematics cableKinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies) {
  CableKinematics k;
  cableKinematics(path, bodies, k);
  return k;
}

void cableKinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies,
                     CableKinematics& k) {
  k.length = k.lengthRate = k.jdotV = 0;
  k.jacobian.clear();
  k.zeroLengthSegments = 0;
  k.directions.resize(path.empty() ? 0 : path.size() - 1);
  PathFrames frames(bodies);
  bool circles = false;
  for (WrapPoint& p : path) {
    p.world = frames.worldPoint(p.body, p.local);
    p.tangentIn = p.tangentOut = p.world;
    circles |= p.radius != 0;
  }
  // Each point's motion serves the segments on both sides of it.
  PointMotion m1 = path.empty() ? PointMotion{} : motionOf(bodies, path[0]);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    WrapPoint& p0 = path[i];
    WrapPoint& p1 = path[i + 1];
    const PointMotion m0 = m1;
    m1 = motionOf(bodies, p1);
    double len;
    Vec2 u;
    if (p0.radius == 0 && p1.radius == 0) {
      const Vec2 d = p1.world - p0.world;
      len = d.norm();
      u = len >= kZeroLength ? Vec2(d / len) : Vec2(1, 0);
    } else {
      const CircleTangent t = circleTangent(p0.world, p0.radius, p1.world, p1.radius);
      len = t.length;
      u = t.u;
      p0.tangentOut = t.from(p0.world, p0.radius);
      p1.tangentIn = t.to(p1.world, p1.radius);
    }
    k.directions[i] = u;
    k.length += len;
    if (len < kZeroLength) {
      ++k.zeroLengthSegments;
      continue;
    }
    const Vec2 w = m1.velocity - m0.velocity;
    const double uw = u.dot(w);
    k.lengthRate += uw;
    k.jdotV += u.dot(m1.accel - m0.accel) + (w.squaredNorm() - uw * uw) / len;
    // Two points on one body keep their distance; two circles with different signed radii on
    // one body do too, but their contributions (each -delta omega) do not cancel term by term.
    if (p0.body != p1.body || p0.radius != p1.radius) {
      addJacobian(k.jacobian, p1.body, Vec3(u.x(), u.y(), u.dot(perp(m1.offset))));
      addJacobian(k.jacobian, p0.body, -Vec3(u.x(), u.y(), u.dot(perp(m0.offset))));
    }
  }
  if (circles) addArcs(path, bodies, k.directions, k);
  std::sort(k.jacobian.begin(), k.jacobian.end(),
            [](const BodyJacobian& a, const BodyJacobian& b) { return a.body < b.body; });
}

void appendLengthHessianTranslation(std::span<const WrapPoint> path,
                                    std::vector<StiffnessBlock>& blocks) {
  // du/dD = (I - u u^T) / l for a tangent between circles too (the tangent points' offsets do
  // not change the turn rate of u), so the blocks use the tangent points.
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int a = path[i].body, b = path[i + 1].body;
    const Vec2 from = path[i].radius == 0 ? path[i].world : path[i].tangentOut;
    const Vec2 to = path[i + 1].radius == 0 ? path[i + 1].world : path[i + 1].tangentIn;
    const Vec2 d = to - from;
    const double len = d.norm();
    if (a == b || len < kZeroLength) continue;
    const Vec2 u = d / len;
    const Eigen::Matrix2d k = (Eigen::Matrix2d::Identity() - u * u.transpose()) / len;
    if (a >= 0) blocks.push_back({a, a, k});
    if (b >= 0) blocks.push_back({b, b, k});
    if (a >= 0 && b >= 0) {
      blocks.push_back({a, b, -k});
      blocks.push_back({b, a, -k});
    }
  }
}

}  // namespace cablelab
