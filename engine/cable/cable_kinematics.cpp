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
#include <limits>

#include "engine/cable/body_frames.h"
#include "engine/cable/cable.h"
#include "engine/cable/circle_wrap.h"
#include "engine/cable/jacobian_entries.h"

namespace cablelab {

namespace {

constexpr double kZeroLength = 1e-12;  // m; shorter segments have no direction

struct PointMotion {
  Vec2 offset = Vec2::Zero();    // world offset from the body origin
  Vec2 velocity = Vec2::Zero();  // world velocity of the point
  Vec2 accel = Vec2::Zero();     // -omega^2 r: the J-dot-v part of its acceleration
};

template <bool kRates = true>
PointMotion motionOf(std::span<const BodyState> bodies, const WrapPoint& p) {
  PointMotion m;
  if (p.body < 0) return m;
  const BodyState& b = bodies[p.body];
  m.offset = p.world - b.position;
  if constexpr (kRates) {
    m.velocity = b.velocity + b.angularVelocity * perp(m.offset);
    m.accel = -b.angularVelocity * b.angularVelocity * m.offset;
  }
  return m;
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

namespace {

// kRates: also J v and J-dot-v (the velocities and the -omega^2 r accelerations of the points).
template <bool kRates>
void kinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies, CableKinematics& k) {
  k.length = k.lengthRate = k.jdotV = 0;
  k.jacobian.clear();
  k.zeroLengthSegments = 0;
  k.directions.resize(path.empty() ? 0 : path.size() - 1);
  BodyFrames frames(bodies);
  bool circles = false;
  for (WrapPoint& p : path) {
    p.world = frames.worldPoint(p.body, p.local);
    p.tangentIn = p.tangentOut = p.world;
    circles |= p.radius != 0;
  }
  // Each point's motion serves the segments on both sides of it.
  PointMotion m1 = path.empty() ? PointMotion{} : motionOf<kRates>(bodies, path[0]);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    WrapPoint& p0 = path[i];
    WrapPoint& p1 = path[i + 1];
    const PointMotion m0 = m1;
    m1 = motionOf<kRates>(bodies, p1);
    double len;
    Vec2 u;
    if (!circles || (p0.radius == 0 && p1.radius == 0)) {
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
    if constexpr (kRates) {
      const Vec2 w = m1.velocity - m0.velocity;
      const double uw = u.dot(w);
      k.lengthRate += uw;
      k.jdotV += u.dot(m1.accel - m0.accel) + (w.squaredNorm() - uw * uw) / len;
    }
    // Two points on one body keep their distance; two circles with different signed radii on
    // one body do too, but their contributions (each -delta omega) do not cancel term by term.
    if (p0.body != p1.body || (circles && p0.radius != p1.radius)) {
      addJacobian(k.jacobian, p1.body, Vec3(u.x(), u.y(), u.dot(perp(m1.offset))));
      addJacobian(k.jacobian, p0.body, -Vec3(u.x(), u.y(), u.dot(perp(m0.offset))));
    }
  }
  if (circles) addArcs(path, bodies, k.directions, k);
}

}  // namespace

void cableKinematics(std::span<WrapPoint> path, std::span<const BodyState> bodies,
                     CableKinematics& k) {
  kinematics<true>(path, bodies, k);
}

void cableLengthJacobian(std::span<WrapPoint> path, std::span<const BodyState> bodies,
                         CableKinematics& k) {
  kinematics<false>(path, bodies, k);
}

void appendLengthHessianTranslation(std::span<const WrapPoint> path,
                                    std::vector<StiffnessBlock>& blocks) {
  // du/dD = (I - u u^T) / l for a tangent between circles too (the tangent points' offsets do
  // not change the turn rate of u), so the blocks use the tangent points.
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int a = path[i].body, b = path[i + 1].body;
    const Vec2 from = path[i].leaving();
    const Vec2 to = path[i + 1].arriving();
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

// A point at arm r from its body's origin moves by at most |dx| + |r| |dtheta| (a chord is no
// longer than its arc) and leaves its linear motion dx + dtheta perp(r) by at most
// |r| (dtheta^2 / 2 + |dtheta|^3 / 6). A segment of length l whose ends move by e < l in all
// changes its length by u . e plus a remainder in [0, e^2 / (2 (l - e))]. Segments on one body
// keep their length.
double lengthRemainderBound(std::span<const WrapPoint> path, std::span<const BodyState> bodies,
                            std::span<const BodyState> moved) {
  auto motion = [&](const WrapPoint& w, double& reach, double& bend) {
    reach = bend = 0;
    if (w.body < 0) return;
    const BodyState &b0 = bodies[w.body], &b1 = moved[w.body];
    const double r = (w.world - b0.position).norm(), turn = std::abs(b1.angle - b0.angle);
    reach = (b1.position - b0.position).norm() + r * turn;
    bend = r * turn * turn * (0.5 + turn / 6);
  };
  if (path.empty()) return 0;
  double bound = 0, reachA, bendA, reachB, bendB;
  motion(path[0], reachA, bendA);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    motion(path[i + 1], reachB, bendB);
    if (path[i].body != path[i + 1].body) {
      const double l = (path[i + 1].world - path[i].world).norm(), e = reachA + reachB;
      if (!(e < 0.5 * l)) return std::numeric_limits<double>::infinity();
      bound += e * e / (2 * (l - e)) + bendA + bendB;
    }
    reachA = reachB, bendA = bendB;
  }
  return bound;
}

namespace {

// Gonzalez's discrete gradient for a path with arcs: G = J(q_mid) + c (q1 - q0), with c chosen
// so that G (q1 - q0) = L(q1) - L(q0) exactly (the metric: metres and radians alike). What
// J(q_mid) misses, L(q1) - L(q0) - J (q1 - q0), is second order in q1 - q0, but the lengths are
// sums over the path, each rounded to some ulps of the points' coordinates: for a body nearly at
// rest that rounding divided by |q1 - q0|^2 grows without bound and G points anywhere (a block
// and tackle in balance: the midpoint solve's Newton never settled, 40 iterations on each of up
// to 20 halvings of the step, 5-9 ms a step). The miss is therefore taken net of the rounding
// bound: nil where rounding can explain it.
double curvedDiscreteGradient(std::span<WrapPoint> path, std::span<const BodyState> q0,
                              std::span<const BodyState> q1, std::vector<BodyJacobian>& gradient) {
  std::vector<WrapPoint> scratch(path.begin(), path.end());
  CableKinematics k;
  cableKinematics(scratch, q0, k);
  const double length0 = k.length;
  std::vector<BodyState> mid(q0.begin(), q0.end());
  for (size_t b = 0; b < mid.size(); ++b) {
    mid[b].position = 0.5 * (q0[b].position + q1[b].position);
    mid[b].angle = 0.5 * (q0[b].angle + q1[b].angle);
  }
  scratch.assign(path.begin(), path.end());
  cableKinematics(scratch, mid, k);
  gradient = k.jacobian;
  cableKinematics(path, q1, k);  // leaves path at q1
  auto delta = [&](int b) {
    return Vec3(q1[b].position.x() - q0[b].position.x(), q1[b].position.y() - q0[b].position.y(),
                q1[b].angle - q0[b].angle);
  };
  double predicted = 0, norm2 = 0;
  for (const BodyJacobian& e : gradient) {
    const Vec3 d = delta(e.body);
    predicted += e.d.dot(d);
    norm2 += d.squaredNorm();
  }
  double coordinates = 0;  // the lengths' rounding scales with the coordinates they come from
  for (const WrapPoint& w : path) coordinates += w.world.norm() + w.radius;
  const double miss = k.length - length0 - predicted;
  const double rounding = 64 * std::numeric_limits<double>::epsilon() * coordinates;
  const double net = std::copysign(std::max(0.0, std::abs(miss) - rounding), miss);
  if (norm2 > 1e-300 && net != 0) {
    const double c = net / norm2;
    for (BodyJacobian& e : gradient) e.d += c * delta(e.body);
  }
  return k.length;
}

}  // namespace

double lengthDiscreteGradient(std::span<WrapPoint> path, std::span<const BodyState> q0,
                              std::span<const BodyState> q1, std::vector<BodyJacobian>& gradient) {
  if (std::any_of(path.begin(), path.end(),
                  [](const WrapPoint& w) { return w.kind == WrapPoint::Kind::Circle; }))
    return curvedDiscreteGradient(path, q0, q1, gradient);
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
  if (path.empty()) return 0;
  double length1 = 0;
  chord(path[0], a0, a1, ta);
  path[0].world = a1;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    Vec2 b0, b1, tb;
    chord(path[i + 1], b0, b1, tb);
    path[i + 1].world = b1;
    const Vec2 d0 = b0 - a0, d1 = b1 - a1;
    const double sum = d0.norm() + d1.norm();
    length1 += d1.norm();
    if (sum >= 2 * kZeroLength && path[i].body != path[i + 1].body) {
      const Vec2 u = (d0 + d1) / sum;
      addJacobian(gradient, path[i + 1].body, Vec3(u.x(), u.y(), u.dot(tb)));
      addJacobian(gradient, path[i].body, -Vec3(u.x(), u.y(), u.dot(ta)));
    }
    a0 = b0, a1 = b1, ta = tb;
  }
  return length1;
}

}  // namespace cablelab
