#include "engine/cable/crossing.h"

#include <algorithm>
#include <cmath>

#include "engine/cable/wrap.h"

namespace cablelab {

MovingPoint MovingPoint::on(std::span<const BodyState> motion, int body, const Vec2& local) {
  const double angle = body < 0 ? 0.0 : motion[body].angle;
  double c, s;
  cosSin(angle, c, s);
  return on(motion, body, local, c, s);
}

MovingPoint MovingPoint::on(std::span<const BodyState> motion, int body, const Vec2& local,
                            double c, double s) {
  MovingPoint m;
  m.local = local;
  m.start = local;
  if (body < 0) return m;
  const BodyState& b = motion[body];
  m.origin = b.position;
  m.velocity = b.velocity;
  m.angle = b.angle;
  m.angularVelocity = b.angularVelocity;
  m.start = b.position + rotate(local, c, s);
  m.speed = m.velocity.norm() + std::abs(m.angularVelocity) * local.norm();
  return m;
}

int crossingSamples(std::span<const MovingPoint> points, double h) {
  double turn = 0;
  for (const MovingPoint& p : points) turn = std::max(turn, std::abs(p.angularVelocity) * h);
  return std::clamp(4 + static_cast<int>(std::ceil(turn / 0.25)), 4, 256);
}

namespace {

// The most a point fixed on a body can move per second over the sub-step: |v| + |omega| |r|.
double speedBound(const MovingPoint& m) {
  return m.speed ? *m.speed : m.velocity.norm() + std::abs(m.angularVelocity) * m.local.norm();
}

}  // namespace

// With n = (b - a) / |b - a|, d/dt cross(n, p - a) is at most |p' - a'| + |n'| |p - a|, and
// |n'| <= |b' - a'| / |b - a|; both are bounded over the sub-step by the points' speed bounds.
bool sideCannotChange(const MovingPoint& a, const MovingPoint& b, const MovingPoint& p, double h,
                      double reach) {
  const Vec2 a0 = a.atStart(), d0 = b.atStart() - a0, pa0 = p.atStart() - a0;
  const double sa = speedBound(a), sb = speedBound(b), sp = speedBound(p);
  const double length = d0.norm(), shortest = length - h * (sa + sb);
  if (!(shortest > 0)) return false;
  const double arm = pa0.norm() + h * (sp + sa);
  const double rate = sp + sa + (sa + sb) * arm / shortest;
  return std::abs(cross(d0, pa0)) / length > 1.01 * h * rate + 1e-12 + reach;
}

std::optional<Crossing> pointCrossesSegment(const MovingPoint& a, const MovingPoint& b,
                                            const MovingPoint& p, WrapSide side, double h,
                                            double reach) {
  if (sideCannotChange(a, b, p, h, reach)) return std::nullopt;
  const MovingPoint pts[] = {a, b, p};
  auto depth = [&](double t) { return wrapSideDistance(a.at(t), b.at(t), p.at(t), side) + reach; };
  auto along = [&](double t) {
    const Vec2 pa = a.at(t), ab = b.at(t) - pa;
    const double l2 = ab.squaredNorm();
    return l2 > 0 ? (p.at(t) - pa).dot(ab) / l2 : -1.0;
  };
  auto between = [&](double t) {
    const double s = along(t);
    return s > 0 && s < 1;
  };
  const auto t = firstRise(depth, between, h, crossingSamples(pts, h), crossingTolerance(h));
  if (!t) return std::nullopt;
  return Crossing{*t, along(*t)};
}

std::optional<double> turnStraightens(const MovingPoint& a, const MovingPoint& p,
                                      const MovingPoint& b, WrapSide side, double h, double reach) {
  if (sideCannotChange(a, b, p, h, reach)) return std::nullopt;
  const MovingPoint pts[] = {a, b, p};
  auto straightening = [&](double t) {
    return -(wrapSideDistance(a.at(t), b.at(t), p.at(t), side) + reach);
  };
  return firstRise(
      straightening, [](double) { return true; }, h, crossingSamples(pts, h), crossingTolerance(h));
}

}  // namespace cablelab
