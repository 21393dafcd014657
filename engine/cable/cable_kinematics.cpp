// Length, Jacobian and J-dot-v of a cable path (thesis section 2.3 as corrected in
// docs/model.md#cable-geometry).
//
// Segment d = p_{i+1} - p_i, u = d / |d|, w = d'(t):
//   d|d|/dt     = u . w
//   d^2|d|/dt^2 = u . dw/dt + (|w|^2 - (u . w)^2) / |d|
// A point fixed on body b at world offset r = R(theta) local moves with v_b + omega perp(r); its
// d/d(x, y, theta) is [I | perp(r)] and its velocity-product acceleration is -omega^2 r.
#include <algorithm>
#include <cmath>

#include "engine/cable/cable.h"

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
  PathFrames frames(bodies);
  for (WrapPoint& p : path) p.world = frames.worldPoint(p.body, p.local);
  // Each point's motion serves the segments on both sides of it.
  PointMotion m1 = path.empty() ? PointMotion{} : motionOf(bodies, path[0]);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const WrapPoint& p0 = path[i];
    const WrapPoint& p1 = path[i + 1];
    const PointMotion m0 = m1;
    m1 = motionOf(bodies, p1);
    const Vec2 d = p1.world - p0.world;
    const double len = d.norm();
    k.length += len;
    if (len < kZeroLength) {
      ++k.zeroLengthSegments;
      continue;
    }
    const Vec2 u = d / len;
    const Vec2 w = m1.velocity - m0.velocity;
    const double uw = u.dot(w);
    k.lengthRate += uw;
    k.jdotV += u.dot(m1.accel - m0.accel) + (w.squaredNorm() - uw * uw) / len;
    if (p0.body != p1.body) {
      addJacobian(k.jacobian, p1.body, Vec3(u.x(), u.y(), u.dot(perp(m1.offset))));
      addJacobian(k.jacobian, p0.body, -Vec3(u.x(), u.y(), u.dot(perp(m0.offset))));
    }
  }
  std::sort(k.jacobian.begin(), k.jacobian.end(),
            [](const BodyJacobian& a, const BodyJacobian& b) { return a.body < b.body; });
}

void appendLengthHessianTranslation(std::span<const WrapPoint> path,
                                    std::vector<StiffnessBlock>& blocks) {
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int a = path[i].body, b = path[i + 1].body;
    const Vec2 d = path[i + 1].world - path[i].world;
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

void lengthDiscreteGradient(std::span<WrapPoint> path, std::span<const BodyState> q0,
                            std::span<const BodyState> q1, std::vector<BodyJacobian>& gradient) {
  gradient.clear();
  // d(point)/d(x, y, theta) over the step: [I | sinc(dtheta / 2) perp(r_mid)].
  auto chord = [&](const WrapPoint& p, Vec2& at0, Vec2& at1, Vec2& turn) {
    at0 = worldPoint(q0, p.body, p.local);
    at1 = worldPoint(q1, p.body, p.local);
    turn = Vec2::Zero();
    if (p.body < 0) return;
    const double dtheta = q1[p.body].angle - q0[p.body].angle;
    const double half = 0.5 * dtheta;
    const double sinc = std::abs(half) < 1e-8 ? 1.0 - half * half / 6 : std::sin(half) / half;
    turn = sinc * perp(rotate(p.local, q0[p.body].angle + half));
  };
  Vec2 a0, a1, ta;
  if (path.empty()) return;
  chord(path[0], a0, a1, ta);
  path[0].world = a1;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    Vec2 b0, b1, tb;
    chord(path[i + 1], b0, b1, tb);
    path[i + 1].world = b1;
    const Vec2 d0 = b0 - a0, d1 = b1 - a1;
    const double sum = d0.norm() + d1.norm();
    if (sum >= 2 * kZeroLength && path[i].body != path[i + 1].body) {
      const Vec2 u = (d0 + d1) / sum;
      addJacobian(gradient, path[i + 1].body, Vec3(u.x(), u.y(), u.dot(tb)));
      addJacobian(gradient, path[i].body, -Vec3(u.x(), u.y(), u.dot(ta)));
    }
    a0 = b0, a1 = b1, ta = tb;
  }
  std::sort(gradient.begin(), gradient.end(),
            [](const BodyJacobian& a, const BodyJacobian& b) { return a.body < b.body; });
}

}  // namespace cablelab
