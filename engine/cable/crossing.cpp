#include "engine/cable/crossing.h"

#include <algorithm>

#include "engine/cable/wrap.h"

namespace cablelab {

MovingPoint MovingPoint::on(std::span<const BodyState> motion, int body, const Vec2& local) {
  MovingPoint m;
  m.local = local;
  if (body < 0) return m;
  const BodyState& b = motion[body];
  m.origin = b.position;
  m.velocity = b.velocity;
  m.angle = b.angle;
  m.angularVelocity = b.angularVelocity;
  return m;
}

int crossingSamples(std::span<const MovingPoint> points, double h) {
  double turn = 0;
  for (const MovingPoint& p : points) turn = std::max(turn, std::abs(p.angularVelocity) * h);
  return std::clamp(4 + static_cast<int>(std::ceil(turn / 0.25)), 4, 256);
}

std::optional<Crossing> pointCrossesSegment(const MovingPoint& a, const MovingPoint& b,
                                            const MovingPoint& p, WrapSide side, double h,
                                            double reach) {
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
  const MovingPoint pts[] = {a, b, p};
  auto straightening = [&](double t) {
    return -(wrapSideDistance(a.at(t), b.at(t), p.at(t), side) + reach);
  };
  return firstRise(
      straightening, [](double) { return true; }, h, crossingSamples(pts, h), crossingTolerance(h));
}

}  // namespace cablelab
